#include <risknav/afraid/afraid_report.h>
#include <risknav/afraid/afraid_speed.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/CPlotImage.h>
#include <risknav/common/config_read.h>
#include <risknav/common/summary_json.h>

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace risknav::common;
using nlohmann::json;

namespace risknav::afraid {
namespace {
std::string num(double v) {
    return std::isfinite(v) ? CCsvWriter::num(v) : "";
}
json finite(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

// The learned experience; returns the file name. After a partial replay under
// another name, so that a complete earlier file of the same name is never
// replaced by it.
std::string writeAfraidFile(const CAfraidLearner& l, COutputDir& out) {
    std::string afraidFile = l.options.afraid_name;
    if (l.partial())
        afraidFile = afraidFile.substr(0, afraidFile.size() - 7) + ".partial.afraid";
    l.grid().save(out.stage(afraidFile));
    return afraidFile;
}

void writeEventsCsv(const CAfraidLearner& l, COutputDir& out) {
    CCsvWriter csv(out.stage("events.csv"), {"t", "rawlog", "entry", "robot_x", "robot_y",
                                             "robot_phi", "obstacle_x", "obstacle_y",
                                             "diff", "obs_cur", "obs_predict", "speed"});
    for (const auto& e : l.events())
        csv.row({CCsvWriter::fixed(e.t, 3), e.rawlog, std::to_string(e.entry),
                 num(e.robotX), num(e.robotY), num(e.robotPhi),
                 e.obstacleFound ? num(e.obstacleX) : "",
                 e.obstacleFound ? num(e.obstacleY) : "", num(e.diff),
                 std::to_string(e.obsCur), std::to_string(e.obsPredict), num(e.speed)});
    csv.close();
}

// trajectory.csv: the localization of every frame.
void writeTrajectoryCsv(const CAfraidLearner& l, COutputDir& out) {
    CCsvWriter csv(out.stage("trajectory.csv"),
                   {"t", "x", "y", "phi", "cov_xx", "cov_yy", "particles",
                    "scan_map_agreement", "localized"});
    for (const auto& e : l.estimates())
        csv.row({CCsvWriter::fixed(e.t, 3), num(e.x), num(e.y), num(e.phi), num(e.covXX),
                 num(e.covYY), std::to_string(e.particles), num(e.agreement),
                 e.localized ? "1" : "0"});
    csv.close();
}

// zones.csv; returns the zones for summary.json.
json writeZonesCsv(const CAfraidLearner& l, COutputDir& out) {
    json zones = json::array();
    CCsvWriter csv(out.stage("zones.csv"),
                   {"zone", "x_min", "x_max", "y_min", "y_max", "area_m2", "peak_level",
                    "robot_events", "obstacle_events", "slow_x_min", "slow_x_max",
                    "slow_y_min", "slow_y_max"});
    for (const auto& z : l.zones()) {
        csv.row({std::to_string(z.id), num(z.xMin), num(z.xMax), num(z.yMin), num(z.yMax),
                 num(z.area), num(z.peak), std::to_string(z.robotEvents),
                 std::to_string(z.obstacleEvents), num(z.slowXMin), num(z.slowXMax),
                 num(z.slowYMin), num(z.slowYMax)});
        zones.push_back(
            {{"id", z.id},
             {"x_min", z.xMin},
             {"x_max", z.xMax},
             {"y_min", z.yMin},
             {"y_max", z.yMax},
             {"area_m2", z.area},
             {"peak_level", z.peak},
             {"robot_events", z.robotEvents},
             {"obstacle_events", z.obstacleEvents},
             {"slow_region", {z.slowXMin, z.slowXMax, z.slowYMin, z.slowYMax}}});
    }
    csv.close();
    return zones;
}

// Nav2 Speed Filter mask (percent): occupancy p = 100 - speed percent in
// the zones, 0 (no limit) elsewhere; "scale" mode, so pixel = 255 (1 - p/100).
void writeSpeedMask(const CAfraidLearner& l, COutputDir& out) {
    const auto& g = l.grid();
    const int sx = g.sizeX(), sy = g.sizeY();
    const int pct = int(std::lround(100.0 * l.options.v_safe / l.options.v_max));
    std::vector<uint8_t> pix(size_t(sx) * sy, 255);
    for (const auto& z : l.zones())
        for (int k : z.slowMask) {
            const int cx = k % sx, cy = k / sx;
            pix[size_t(sy - 1 - cy) * sx + cx] =
                uint8_t(std::lround(255.0 * (1.0 - (100 - pct) / 100.0)));
        }
    std::ofstream f(out.stage("speed_mask.pgm"), std::ios::binary);
    f << "P5\n" << sx << " " << sy << "\n255\n";
    f.write(reinterpret_cast<const char*>(pix.data()), std::streamsize(pix.size()));
    f.close();
    char yaml[600];
    std::snprintf(yaml, sizeof(yaml),
                  "# Nav2 Speed Filter mask from risknav-afraid-learn: inside the "
                  "learned zones the\n"
                  "# speed is limited to %d %% of the maximum (v_safe / v_max), "
                  "elsewhere no limit.\n"
                  "# Use with a CostmapFilterInfo of type 1 (percent), base 100.0, "
                  "multiplier -1.0.\n"
                  "image: speed_mask.pgm\nmode: scale\nresolution: %.6f\norigin: "
                  "[%.6f, %.6f, 0.0]\n"
                  "negate: 0\noccupied_thresh: 1.0\nfree_thresh: 0.0\n",
                  pct, g.resolution(), g.xMin(), g.yMin());
    out.writeText("speed_mask.yaml", yaml);
}

// afraid.png: level as a heat overlay, raw events as dots, zones outlined.
void drawAfraidImage(const CAfraidLearner& l, double peak, COutputDir& out) {
    const double threshold = l.options.zone_threshold;
    CMapImage img(l.map());
    img.heatOverlay(l.level(), 0.f, float(std::max(peak, threshold * 2)), "afraid level",
                    0.65, float(0.25 * threshold));
    img.polyline(l.trajectory(), {150, 150, 150}, 1);
    for (const auto& e : l.events()) {
        img.circle({e.robotX, e.robotY}, 0.04, {0, 0, 0}, 1, true);
        if (e.obstacleFound)
            img.circle({e.obstacleX, e.obstacleY}, 0.05, {220, 0, 0}, 1, true);
    }
    for (const auto& z : l.zones()) {
        img.polyline({{z.xMin, z.yMin},
                      {z.xMax, z.yMin},
                      {z.xMax, z.yMax},
                      {z.xMin, z.yMax},
                      {z.xMin, z.yMin}},
                     {200, 0, 200}, 2);
        img.text({z.xMin, z.yMax + 0.15}, "zone " + std::to_string(z.id), {150, 0, 150});
    }
    img.legendLine("robot path (MCL)", {150, 150, 150}, 1);
    img.legendMarker("robot at an event", CMapImage::TMarker::Circle, {0, 0, 0});
    img.legendMarker("unexpected obstacle", CMapImage::TMarker::Circle, {220, 0, 0});
    img.legendLine("zone (level > " + CCsvWriter::num(threshold, 3) + ")", {200, 0, 200},
                   2);
    char title[200];
    std::snprintf(title, sizeof(title),
                  "risknav-afraid-learn: %zu new events (%llu in all), %zu zones%s",
                  l.events().size(),
                  static_cast<unsigned long long>(l.grid().totalRobotEvents()),
                  l.zones().size(), l.partial() ? "  [PARTIAL]" : "");
    img.setTitle(title);
    img.save(out.stage("afraid.png"));
}

// Zone limits as vertical lines on a plot along the route axis.
void zoneLines(CPlotImage& plot, const CAfraidLearner& l, const TRouteAxis& a) {
    for (const auto& z : l.zones()) {
        const auto [from, to] = zoneSpan(z, a);
        plot.addVLine(from, "zone " + std::to_string(z.id), {200, 0, 200});
        plot.addVLine(to, "", {200, 0, 200});
    }
}

// profile.png: events per 10 cm and the level along the route's principal
// axis; returns the axis for summary.json.
json drawProfile(const CAfraidLearner& l, const TRouteAxis& a, double peak,
                 COutputDir& out) {
    const size_t nb = a.pos.size();
    std::vector<double> counts(nb, 0.0), level(nb, 0.0);
    for (const auto& e : l.events())
        counts[size_t(a.binOf(e.robotX, e.robotY))] += 1;
    for (const auto& p : l.trajectory()) {
        const auto b = size_t(a.binOf(p.x, p.y));
        level[b] = std::max(level[b], l.levelAt(p.x, p.y));
    }
    double cmax = 1;
    for (double c : counts)
        cmax = std::max(cmax, c);
    std::vector<double> scaled(level.size());
    for (size_t i = 0; i < level.size(); i++)
        scaled[i] = level[i] / std::max(peak, 1e-9) * cmax;
    CPlotImage plot;
    plot.setXLabel(
        "position along the route's main axis (world coordinates projected) [m]");
    plot.setYLabel("events per 10 cm");
    plot.addSeries("afraid events (robot position), per 10 cm", a.pos, counts,
                   {40, 40, 40}, 1);
    plot.addSeries("generalized level (scaled to the event maximum)", a.pos, scaled,
                   {220, 40, 0}, 2);
    zoneLines(plot, l, a);
    plot.setTitle(
        "afraid events and the learned level along the route (cf. Choi et al. Figs. "
        "8-9)");
    plot.save(out.stage("profile.png"));
    return {
        {"direction", {a.ux, a.uy}}, {"from_m", a.pos.front()}, {"to_m", a.pos.back()}};
}

// speed.png: the speed limit along the axis and the 10 m comparison's figures.
void drawSpeedPlot(const CAfraidLearner& l, const TRouteSpeedProfile& r,
                   COutputDir& out) {
    const auto& pos = r.axis.pos;
    CPlotImage sp;
    sp.setXLabel(
        "position along the route's main axis (world coordinates projected) [m]");
    sp.setYLabel("speed [m/s]");
    sp.addSeries("v = min(v_behaviour, v_afraid), driving towards +axis", pos, r.speed,
                 {0, 90, 200}, 2);
    std::vector<double> safe(pos.size(), l.options.v_safe);
    sp.addSeries("before learning: v_safe everywhere", pos, safe, {120, 120, 120}, 1,
                 true);
    zoneLines(sp, l, r.axis);
    if (r.tenMetre) {
        const auto& c = *r.tenMetre;
        char t[200];
        std::snprintf(t, sizeof(t),
                      "speed limit along the route: %.1f m from %.1f m in %.1f s "
                      "(%.1f s at v_safe)",
                      c.lengthM, c.fromM, c.timeAfterS, c.timeBeforeS);
        sp.setTitle(t);
    } else
        sp.setTitle("speed limit along the route (no zone: v_max everywhere)");
    sp.save(out.stage("speed.png"));
}

json tenMetreJson(const std::optional<TRouteSpeedProfile>& r) {
    if (!r || !r->tenMetre)
        return nullptr;
    const auto& c = *r->tenMetre;
    return {{"from_m", c.fromM},
            {"to_m", c.toM},
            {"time_before_s", c.timeBeforeS},
            {"time_after_s", c.timeAfterS},
            {"mean_speed_after", c.meanSpeedAfter}};
}

// The results of the run for summary.json (files and figures come from the
// steps above).
json summaryJson(const CAfraidLearner& l, const std::string& afraidFile,
                 const json& zones, double peak, const json& axis, const json& tenMetre) {
    const auto& g = l.grid();
    json j;
    j["ten_metre_section"] = tenMetre;
    j["status"] = l.partial() ? "partial" : (l.diverged() ? "diverged" : "ok");
    j["partial"] = l.partial();
    j["error"] = l.error();
    j["rawlogs"] = l.processedRawlogs();  // those replayed (the last maybe in part)
    j["frames"] = l.frames();
    // Without replayed frames (a merge-only run) the counts are 0 and the
    // fractions and errors null: nothing was localized, nothing is measured.
    j["localization"] = {
        {"localized_frames", l.localizedFrames()},
        {"localized_fraction",
         l.frames() ? json(double(l.localizedFrames()) / l.frames()) : json(nullptr)},
        {"mean_scan_map_agreement", finite(l.meanMatch())},
        {"diverged", l.diverged()},
        {"mcl_error_mean_m", finite(l.mclErrorMean())},
        {"mcl_error_max_m", finite(l.mclErrorMax())},
        {"mcl_error_samples", l.mclErrorSamples()},
        {"final_pose", l.estimates().empty()
                           ? json(nullptr)
                           : json({l.estimates().back().x, l.estimates().back().y,
                                   l.estimates().back().phi * 180 / M_PI})}};
    j["events"] = l.events().size();
    j["events_total"] = g.totalRobotEvents();
    j["runs_total"] = g.runs;
    j["afraid_file"] = afraidFile;
    j["afraid_in"] = l.options.afraid_in;
    j["zones"] = zones;
    j["peak_level"] = peak;
    j["profile_axis"] = axis;
    const auto& o = l.options;
    const auto& d = l.detector;
    j["parameters"] = {{"kernel_bandwidth", o.krr.bandwidth},
                       {"kernel_lambda", o.krr.lambda},
                       {"zone_threshold", o.zone_threshold},
                       {"v_max", o.v_max},
                       {"v_safe", o.v_safe},
                       {"t_delay", d.robot.t_delay},
                       {"decel", d.robot.decel},
                       {"robot_radius", d.robot.radius},
                       {"beta", d.options.beta},
                       {"lateral_margin", d.options.lateral_margin},
                       {"half_width", d.halfWidth()},
                       {"foot_step", d.options.foot_step},
                       {"diff_threshold", d.options.diff_threshold}};
    return j;
}
}  // namespace

json writeAfraidReport(const CAfraidLearner& l, COutputDir& out) {
    // Results first (pure), then the files, in the order they are staged.
    double peak = 0;
    for (float v : l.level())
        peak = std::max(peak, double(v));
    TAfraidSpeedParams sp;
    sp.vMax = l.options.v_max;
    sp.vSafe = l.options.v_safe;
    sp.threshold = l.options.zone_threshold;
    sp.tDelay = l.detector.robot.t_delay;
    sp.decel = l.detector.robot.decel;
    const auto route =
        routeSpeedProfile([&](double x, double y) { return l.levelAt(x, y); },
                          l.trajectory(), l.zones(), sp);

    const std::string afraidFile = writeAfraidFile(l, out);
    writeEventsCsv(l, out);
    writeTrajectoryCsv(l, out);
    const json zones = writeZonesCsv(l, out);
    writeSpeedMask(l, out);
    drawAfraidImage(l, peak, out);
    json axis = nullptr;
    if (route) {
        axis = drawProfile(l, route->axis, peak, out);
        drawSpeedPlot(l, *route, out);
    }
    return summaryJson(l, afraidFile, zones, peak, axis, tenMetreJson(route));
}

void runAfraidLearnApp(const TAppContext& ctx) {
    const auto t0 = std::chrono::steady_clock::now();
    CAfraidLearner l;
    l.loadFromConfigFile(ctx.cfg, ctx.args.extra, ctx.args.seed);
    COutputDir out(ctx.args.outDir,
                   ctx.info.name);  // checked before the replay, not after it
    l.run(ctx.args.quiet);
    l.generalize();
    // A partial replay never replaces a complete run's files: its results go
    // to <out>/partial/.
    if (l.partial())
        out.commitInto("partial");
    json summary = summaryHeader(ctx, l.options.seed);
    summary.update(writeAfraidReport(l, out));
    mrpt::config::CConfigFileMemory effective;
    l.saveToConfigFile(effective);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    summary["timing"] = {{"wall_time_s", wall},
                         {"replay_s", l.replaySeconds()},
                         {"frames_per_s", l.frames() && l.replaySeconds() > 0
                                              ? json(l.frames() / l.replaySeconds())
                                              : json(nullptr)}};
    // (without a route there is no profile.png and speed.png: the commit
    // removes an earlier run's, as every file of its set this run does not
    // write)
    commitRun(ctx, out, summary, effective);
    if (l.partial())  // results up to the bad entry are saved, marked partial
        throw CBadInputError(l.error() + "; partial results in " +
                             out.finalPath("partial"));
    if (ctx.args.quiet)
        return;
    const auto& g = l.grid();
    if (l.options.rawlogs.empty())  // merge only
        std::fprintf(stderr,
                     "%s: merged %zu .afraid files (%u runs, %llu frames, %llu events), "
                     "%zu zones -> %s\n",
                     ctx.info.name.c_str(), l.options.afraid_in.size(), g.runs,
                     static_cast<unsigned long long>(g.frames),
                     static_cast<unsigned long long>(g.totalRobotEvents()),
                     l.zones().size(), out.dir().c_str());
    else
        std::fprintf(stderr, "%s: %zu frames, %zu events, %zu zones%s -> %s\n",
                     ctx.info.name.c_str(), l.frames(), l.events().size(),
                     l.zones().size(), l.diverged() ? " (LOCALIZATION DIVERGED)" : "",
                     out.dir().c_str());
}

}  // namespace risknav::afraid
