#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/CPlotImage.h>
#include <risknav/nav/navigate_report.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using nlohmann::json;

namespace risknav::nav {
namespace {
std::string num(double v) {
    return CCsvWriter::num(v, 9);
}

json finiteOrNull(double x) {
    return std::isfinite(x) ? json(x) : json(nullptr);
}

// One colour per limiter, the same in every picture.
TRgb limiterColour(const std::string& name) {
    if (name.empty() || name == "none")
        return {0, 110, 220};
    if (name == "CStoppingDistanceLimiter")
        return {220, 30, 30};
    if (name == "CAfraidSpeedLimiter")
        return {240, 140, 0};
    if (name == "CAdaptiveSpeedLimiter")
        return {0, 160, 70};
    if (name == "turn_in_place")
        return {120, 120, 120};
    if (name == "unstick")
        return {20, 20, 20};
    return {150, 60, 190};
}
}  // namespace

void writeCyclesCsv(const TNavRunResult& r, double startTime, const std::string& path) {
    CCsvWriter csv(path, {"cycle", "t", "true_x", "true_y", "true_phi_deg", "believed_x",
                          "believed_y", "believed_phi_deg", "pose_error_m", "speed",
                          "command", "desired", "limit", "limiter", "reason",
                          "clearance_m", "waypoint", "distance_m", "step_ms"});
    for (const auto& c : r.cycles)
        csv.row({std::to_string(c.cycle), CCsvWriter::fixed(startTime + c.t, 3),
                 num(c.truePose.x), num(c.truePose.y), num(c.truePose.phi * 180 / M_PI),
                 num(c.believedPose.x), num(c.believedPose.y),
                 num(c.believedPose.phi * 180 / M_PI), num(c.poseError), num(c.speed),
                 num(c.command), num(c.desired), num(c.limit),
                 c.limiter.empty() ? "none" : c.limiter, c.reason, num(c.clearance),
                 std::to_string(c.waypoint), num(c.distance), num(c.stepMs)});
    csv.close();
}

void writeEventsCsv(const TNavRunResult& r, double startTime, const std::string& path) {
    struct TRow {
        double t;
        std::string kind, source, detail;
        int waypoint;
        double x, y;
    };
    std::vector<TRow> rows;
    for (const auto& e : r.events)
        rows.push_back({e.t, e.kind, "navigator", e.detail, e.waypoint, e.x, e.y});
    for (const auto& e : r.agentEvents)
        rows.push_back({e.t, e.kind, e.source, e.agent, -1, e.x, e.y});
    for (const auto& e : r.safety.corridorEntries())
        rows.push_back(
            {e.t, "inside_stopping_distance", e.source, e.agent, -1, e.x, e.y});
    for (const auto& e : r.safety.events()) {
        char b[64];
        std::snprintf(b, sizeof(b), "%s, gap %.3f m", e.object.c_str(), e.gap);
        rows.push_back({e.t, e.kind, "safety", b, -1, e.ox, e.oy});
    }
    std::stable_sort(rows.begin(), rows.end(),
                     [](const TRow& a, const TRow& b) { return a.t < b.t; });
    CCsvWriter csv(path, {"t", "kind", "source", "waypoint", "x", "y", "detail"});
    for (const auto& e : rows)
        csv.row({CCsvWriter::fixed(startTime + e.t, 3), e.kind, e.source,
                 std::to_string(e.waypoint), num(e.x), num(e.y), e.detail});
    csv.close();
}

void drawTrajectory(const CNavigationRun& run, const TNavRunResult& r,
                    const std::string& title, const std::string& path,
                    const std::vector<uint8_t>* zoneMask) {
    const auto& world = run.world;
    CMapImage img(world.grid());
    if (zoneMask)
        img.paintCells(*zoneMask, {255, 214, 150});
    for (const auto& d : world.agents.doors)
        img.segment({d.door[0], d.door[1]}, {d.door[2], d.door[3]}, {230, 120, 0}, 5);
    for (const auto& k : world.agents.clutter)
        img.circle({k.x, k.y}, k.radius, {140, 90, 40}, 1, true);
    for (const auto& [id, tr] : r.people)
        img.polyline(tr, {170, 120, 210}, 1);
    std::vector<TPoint2D> route{{run.options.start.x, run.options.start.y}};
    for (const auto& w : run.waypoints.waypoints)
        route.emplace_back(w.target.x, w.target.y);
    img.polyline(route, {200, 200, 200}, 4, true);
    // the global planner's plans: every one followed, the later ones darker
    for (size_t k = 0; k < r.planPaths.size(); k++)
        img.polyline(r.planPaths[k], k == 0 ? TRgb{120, 170, 255} : TRgb{40, 90, 200}, 1);
    double vmax = world.robot.max_v;
    for (const auto& c : r.cycles)
        vmax = std::max(vmax, c.speed);
    // The path in pieces, each coloured by the speed of its cycle.
    const int perCycle = int(std::lround(run.options.nav_period / run.options.sim_dt));
    for (size_t i = 0; i + 1 < r.track.size(); i++) {
        const size_t c = std::min(r.cycles.size() - 1, i / size_t(std::max(1, perCycle)));
        const double v = r.cycles.empty() ? 0 : r.cycles[c].speed;
        img.segment(r.track[i], r.track[i + 1], CMapImage::colourOf(v, 0, vmax), 3);
    }
    img.colourBar(0, float(vmax), "speed [m/s]");
    for (size_t i = 0; i < run.waypoints.waypoints.size(); i++) {
        const auto& w = run.waypoints.waypoints[i].target;
        const auto it = run.tags.find(i);
        img.marker({w.x, w.y}, CMapImage::TMarker::Plus,
                   it == run.tags.end() ? TRgb{90, 90, 90} : TRgb{0, 150, 150}, 10, 2);
    }
    for (const auto& e : r.agentEvents)
        if (e.kind == "emerge")
            img.marker({e.x, e.y}, CMapImage::TMarker::Triangle, {230, 120, 0}, 10, 2);
    for (const auto& e : r.safety.events())
        img.marker({e.ox, e.oy},
                   e.kind == "collision" ? CMapImage::TMarker::Cross
                                         : CMapImage::TMarker::Circle,
                   e.kind == "collision" ? TRgb{220, 0, 0} : TRgb{200, 0, 200}, 12, 2);
    for (const auto& e : r.events)
        if (e.kind == "viewpoint" || e.kind == "sensing")
            img.marker({e.x, e.y}, CMapImage::TMarker::Square, {0, 150, 150}, 12, 2);
    size_t unsticks = 0;
    for (size_t i = 0; i < r.cycles.size(); i++)
        if (r.cycles[i].limiter == "unstick" &&
            (i == 0 || r.cycles[i - 1].limiter != "unstick")) {
            const auto& p = r.cycles[i].truePose;
            img.marker({p.x, p.y}, CMapImage::TMarker::Triangle, {20, 20, 20}, 12, 2);
            unsticks++;
        }
    const auto& s = run.options.start;
    img.marker({s.x, s.y}, CMapImage::TMarker::Square, {0, 160, 0}, 14, 2);
    if (!r.track.empty())
        img.marker(r.track.back(), CMapImage::TMarker::Star, {0, 0, 0}, 14, 2);
    img.legendLine("route (waypoints +)", {200, 200, 200}, 4);
    if (!r.planPaths.empty())
        img.legendLine("global plan (replans darker)", {40, 90, 200}, 1);
    img.legendLine("path, coloured by speed (bar)",
                   CMapImage::colourOf(0.8 * vmax, 0, vmax), 3);
    if (!r.people.empty())
        img.legendLine("people's tracks", {170, 120, 210}, 1);
    if (zoneMask)
        img.legendLine("afraid zones", {255, 214, 150}, 8);
    if (!world.agents.doors.empty())
        img.legendLine("door", {230, 120, 0}, 5);
    if (std::any_of(r.agentEvents.begin(), r.agentEvents.end(),
                    [](const sim::TAgentEvent& e) { return e.kind == "emerge"; }))
        img.legendMarker("person emerged", CMapImage::TMarker::Triangle, {230, 120, 0});
    if (!world.agents.clutter.empty())
        img.legendMarker("clutter (not on the map)", CMapImage::TMarker::Circle,
                         {140, 90, 40});
    if (r.collisions())
        img.legendMarker("collision", CMapImage::TMarker::Cross, {220, 0, 0});
    if (r.safety.nearMisses())
        img.legendMarker("near miss", CMapImage::TMarker::Circle, {200, 0, 200});
    if (unsticks)
        img.legendMarker("unstick turn (" + std::to_string(unsticks) + ")",
                         CMapImage::TMarker::Triangle, {20, 20, 20});
    if (!run.tags.empty())
        img.legendMarker("viewpoint / sensing point", CMapImage::TMarker::Square,
                         {0, 150, 150});
    img.legendMarker("start", CMapImage::TMarker::Square, {0, 160, 0});
    img.legendMarker("end", CMapImage::TMarker::Star, {0, 0, 0});
    img.setTitle(title);
    img.save(path);
}

void drawSpeedProfile(const TNavRunResult& r, const std::string& title,
                      const std::string& path) {
    CPlotImage plot;
    plot.setTitle(title);
    plot.setXLabel("distance travelled [m]");
    plot.setYLabel("speed [m/s]");
    std::vector<double> d, lim;
    for (const auto& c : r.cycles) {
        d.push_back(c.distance);
        lim.push_back(c.limit);
    }
    if (!d.empty())
        plot.addSeries("command bound: min(MRPT's speed, every limit)", d, lim,
                       {160, 160, 160}, 1, true);
    // The speed in runs of one winning limiter, each in its limiter's colour.
    std::set<std::string> labelled;
    for (size_t i = 0; i < r.cycles.size();) {
        const std::string who =
            r.cycles[i].limiter.empty() ? "none" : r.cycles[i].limiter;
        size_t j = i;
        std::vector<double> x, y;
        while (j < r.cycles.size() &&
               (r.cycles[j].limiter.empty() ? "none" : r.cycles[j].limiter) == who) {
            x.push_back(r.cycles[j].distance);
            y.push_back(r.cycles[j].speed);
            j++;
        }
        if (j < r.cycles.size()) {  // join to the next run
            x.push_back(r.cycles[j].distance);
            y.push_back(r.cycles[j].speed);
        }
        const std::string label =
            labelled.insert(who).second
                ? (who == "none"
                       ? "robot speed, no limiter active"
                       : (who == "turn_in_place"
                              ? "robot speed, turning in place to a waypoint behind"
                              : (who == "unstick"
                                     ? "robot speed, turning a stuck robot to its target"
                                     : "robot speed, limited by " + who)))
                : "";
        plot.addSeries(label, x, y, limiterColour(who), 2);
        i = j;
    }
    // A turn in place adds no distance: each unstick turn is a line where it began.
    bool unstickLabelled = false;
    for (size_t i = 0; i < r.cycles.size(); i++)
        if (r.cycles[i].limiter == "unstick" &&
            (i == 0 || r.cycles[i - 1].limiter != "unstick")) {
            // turns at one spot would print their labels over each other
            plot.addVLine(r.cycles[i].distance, unstickLabelled ? "" : "unstick turn",
                          limiterColour("unstick"));
            unstickLabelled = true;
        }
    for (const auto& e : r.events)
        if (e.kind == "viewpoint" || e.kind == "sensing") {
            double dist = 0;
            for (const auto& c : r.cycles)
                if (c.t <= e.t)
                    dist = c.distance;
            plot.addVLine(dist, e.kind, {0, 150, 150});
        }
    plot.save(path);
}

json runSummary(const CNavigationRun& run, const TNavRunResult& r) {
    json j;
    j["status"] = r.status;
    j["navigation_error"] = r.navError;
    j["route"] = run.routeName;
    j["localization"] = run.options.localization;
    j["time_s"] = r.time;
    j["distance_m"] = r.distance;
    j["cycles"] = r.cycles.size();
    j["waypoints"] = r.waypointCount;
    j["waypoints_reached"] = r.waypointsReached;
    j["waypoints_skipped"] = r.waypointsSkipped;
    j["goal_reached"] = r.status == "goal_reached";
    j["collisions"] = r.collisions();
    j["collisions_static"] = r.safety.collisionsStatic();
    j["near_misses"] = r.safety.nearMisses();
    j["inside_stopping_distance"] = r.safety.corridorEntries().size();
    j["min_clearance_static_m"] = finiteOrNull(r.safety.minGapStatic());
    j["min_clearance_agents_m"] = finiteOrNull(r.safety.minGapAgents());
    json tpl = json::object();
    for (const auto& [k, v] : r.timePerLimiter)
        tpl[k] = v;
    j["time_per_limiter_s"] = tpl;
    j["pose_error_final_m"] = r.finalPoseError;
    j["pose_error_max_m"] = r.maxPoseError;
    size_t emerged = 0;
    for (const auto& e : r.agentEvents)
        emerged += e.kind == "emerge";
    j["emergences"] = emerged;
    json ev = json::array();
    for (const auto& e : r.events)
        if (e.kind == "viewpoint" || e.kind == "sensing" || e.kind == "navigation_error")
            ev.push_back({{"t", e.t},
                          {"kind", e.kind},
                          {"waypoint", e.waypoint},
                          {"detail", e.detail}});
    j["tagged_events"] = ev;
    const auto& p = r.cycles.empty() ? run.options.start : r.cycles.back().truePose;
    j["end_pose"] = {p.x, p.y, p.phi * 180 / M_PI};
    j["rawlog_frames"] = r.rawlogFrames;
    j["mrpt_errors"] = r.mrptErrors;
    j["mrpt_first_error"] = r.firstMrptError;
    j["goal_true_distance_m"] = finiteOrNull(r.goalTrueDistance);
    j["localization_lost"] = r.localizationLost;
    j["global_planner"] = run.options.global_planner;
    if (run.options.global_planner != "none") {
        json replans = json::object();
        int plans = 0;
        double msMax = 0, msSum = 0;
        for (const auto& e : r.plans) {
            if (e.why == "new_target")
                plans++;
            else
                replans[e.why] = replans.value(e.why, 0) + 1;
            msMax = std::max(msMax, e.ms);
            msSum += e.ms;
        }
        j["plan"] = {{"first_length_m", r.firstPlanLength},
                     {"plans", plans},
                     {"replans", replans},
                     {"plan_ms_max", msMax},
                     {"plan_ms_mean", r.plans.empty() ? 0.0 : msSum / r.plans.size()},
                     {"no_path", r.noPathFailure}};
        if (run.options.global_planner == "risk") {
            json choices = json::array();
            for (const auto& ch : r.routeChoices) {
                json cands = json::array();
                for (size_t i = 0; i < ch.score.size(); i++)
                    cands.push_back({{"length_m", ch.length[i]},
                                     {"U", finiteOrNull(ch.score[i])},
                                     {"chosen", i == ch.chosen}});
                choices.push_back({{"chosen", ch.chosen},
                                   {"reason", ch.reason},
                                   {"candidates", cands}});
            }
            j["plan"]["route_choices"] = choices;
        }
    }
    j["timing"] = {
        {"wall_time_s", r.wallSeconds},
        {"navigation_step_s", r.navStepSeconds},
        {"steps_per_s", r.navStepSeconds > 0 ? r.cycles.size() / r.navStepSeconds : 0.0},
        {"realtime_factor", r.wallSeconds > 0 ? r.time / r.wallSeconds : 0.0}};
    return j;
}

}  // namespace risknav::nav
