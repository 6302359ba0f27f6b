#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/CPlotImage.h>
#include <risknav/common/CProgress.h>
#include <risknav/common/config_read.h>
#include <risknav/common/summary_json.h>
#include <risknav/speed/explore_app.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

using namespace risknav::common;
using nlohmann::json;

namespace risknav::speed {
namespace {
const TRgb kModeColours[] = {{220, 30, 30}, {30, 90, 220},  {20, 150, 60},
                             {230, 140, 0}, {140, 60, 170}, {0, 150, 160}};
TRgb reasonColour(const std::string& r) {
    if (r == "none")
        return {20, 150, 60};
    if (r == "narrow")
        return {230, 120, 0};
    if (r == "undecided")
        return {30, 90, 220};
    if (r == "obstacle")
        return {200, 0, 160};
    if (r == "goal")
        return {140, 60, 170};
    if (r == "look_around")
        return {120, 120, 120};
    return {200, 30, 30};  // unreachable
}

double median(std::vector<double> v) {
    if (v.empty())
        return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}
}  // namespace

json modeSummary(const TModeResult& r, const TSpeedControlOptions& o) {
    json j;
    j["mode"] = r.name;
    j["time_s"] = r.time;
    j["distance_m"] = r.distance;
    j["cycles"] = r.cycles.size();
    j["collisions"] = r.collisions + r.collisionsStatic;
    j["collisions_static"] = r.collisionsStatic;
    j["near_misses"] = r.nearMisses;
    j["min_clearance_m"] = std::isfinite(r.minClearance) ? json(r.minClearance) : json();
    j["margin_broken_cycles"] = r.marginBrokenCycles;
    json ts = json::object();
    for (size_t k = 0; k < o.speeds.size(); k++)
        ts[numberText(o.speeds[k])] = r.timeAtSpeed[k];
    j["time_at_speed_s"] = ts;
    j["time_stopped_or_turning_s"] = r.timeStopped;
    j["destinations"] = r.destinationStatus;
    // where the robot believed it had arrived: the true distance to the
    // destination, and the belief's own error there (null: never arrived)
    auto metres = [](const std::vector<double>& v) {
        json a = json::array();
        for (double e : v)
            a.push_back(std::isfinite(e) ? json(e) : json());
        return a;
    };
    j["destination_error_m"] = metres(r.destinationError);
    j["destination_belief_error_m"] = metres(r.destinationBeliefError);
    j["destinations_reached"] =
        std::count(r.destinationStatus.begin(), r.destinationStatus.end(), "reached");
    j["destinations_localization_error"] = std::count(
        r.destinationStatus.begin(), r.destinationStatus.end(), "localization_error");
    j["all_reached"] = r.allReached();
    json reasons = json::object();
    for (const auto& c : r.cycles)
        reasons[c.reason] = reasons.value(c.reason, 0) + 1;
    j["cycles_by_reason"] = reasons;
    std::vector<double> ms;
    for (const auto& c : r.cycles)
        ms.push_back(c.computeMs);
    j["cycle_compute_ms_median"] = median(ms);
    j["cycle_compute_ms_max"] =
        ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end());
    // the scan matcher (ego_motion = scan_matching): its share of the cycle
    // and how many of its matches were taken
    if (r.localization) {
        std::vector<double> lm;
        for (const auto& c : r.cycles)
            lm.push_back(c.localizationMs);
        const auto& st = *r.localization;
        j["localization"] = {
            {"scans", st.scans},
            {"matches_accepted", st.accepted},
            {"matches_refused", st.refused},
            {"keyframes", st.keyframes},
            {"map_points", r.localizationMapPoints},
            {"cycle_ms_median", median(lm)},
            {"cycle_ms_max", lm.empty() ? 0.0 : *std::max_element(lm.begin(), lm.end())}};
    }
    return j;
}

namespace {
/** cycles.csv: one row per cycle of every mode. */
void writeCyclesCsv(const CExplorer& ex, const std::vector<TModeResult>& runs,
                    COutputDir& out) {
    const auto& o = ex.speed;
    std::vector<std::string> head = {"mode",
                                     "cycle",
                                     "t",
                                     "x",
                                     "y",
                                     "phi_deg",
                                     "ego_x",
                                     "ego_y",
                                     "ego_phi_deg",
                                     "distance",
                                     "speed",
                                     "commanded",
                                     "reason",
                                     "d_undecided",
                                     "destination",
                                     "temporary_target",
                                     "margin_broken"};
    for (double v : o.speeds)
        head.push_back("cost_to_go_" + numberText(v));
    head.push_back("compute_ms");
    CCsvWriter csv(out.stage("cycles.csv"), head);
    for (const auto& r : runs)
        for (const auto& c : r.cycles) {
            std::vector<std::string> row = {
                r.name,
                std::to_string(c.cycle),
                CCsvWriter::fixed(c.t, 3),
                CCsvWriter::num(c.truePose.x, 6),
                CCsvWriter::num(c.truePose.y, 6),
                CCsvWriter::num(c.truePose.phi * 180 / M_PI, 6),
                CCsvWriter::num(c.egoPose.x, 6),
                CCsvWriter::num(c.egoPose.y, 6),
                CCsvWriter::num(c.egoPose.phi * 180 / M_PI, 6),
                CCsvWriter::num(c.distance, 6),
                CCsvWriter::num(c.chosen),
                CCsvWriter::num(c.commanded),
                c.reason,
                CCsvWriter::num(c.dUndecided, 6),  // empty: none on the way
                std::to_string(c.destination),
                c.temporaryTarget ? "1" : "0",
                c.marginBroken ? "1" : "0"};
            for (size_t k = 0; k < o.speeds.size(); k++)
                row.push_back(k < c.costToGo.size()  // empty: no path (or cut off)
                                  ? CCsvWriter::num(c.costToGo[k], 6)
                                  : "");
            row.push_back(CCsvWriter::num(c.computeMs, 4));
            csv.row(row);
        }
    csv.close();
}

/** trace.png: the observation points of each mode (their spacing is the
 * speed). */
void writeTraceImage(const CExplorer& ex, const std::vector<TModeResult>& runs,
                     COutputDir& out) {
    const auto& o = ex.speed;
    CMapImage img(ex.world.grid());
    const auto& adaptive = runs.front();
    img.setTitle("risknav-explore: observation points (one per " +
                 numberText(o.cycle_time) + " s cycle); " + adaptive.name + " " +
                 numberText(std::round(adaptive.time * 10) / 10) + " s");
    for (size_t m = 0; m < runs.size(); m++) {
        const TRgb c = kModeColours[m % 6];
        std::vector<mrpt::math::TPoint2D> line;
        for (const auto& p : runs[m].observations)
            line.emplace_back(p.x, p.y);
        img.polyline(line, c, 1);
        for (const auto& p : line)
            img.circle(p, 0.05, c, 1, m == 0);
        char label[96];
        std::snprintf(label, sizeof(label), "%s: %.1f s, %d collisions",
                      runs[m].name.c_str(), runs[m].time,
                      runs[m].collisions + runs[m].collisionsStatic);
        img.legendLine(label, c);
    }
    const auto& d = ex.explore.destinations;
    for (size_t k = 0; k + 1 < d.size(); k += 2) {
        img.marker({d[k], d[k + 1]}, CMapImage::TMarker::Star, {0, 0, 0}, 12);
        img.text({d[k] + 0.15, d[k + 1] + 0.15}, "D" + std::to_string(k / 2 + 1),
                 {0, 0, 0});
    }
    img.marker({ex.explore.start[0], ex.explore.start[1]}, CMapImage::TMarker::Square,
               {0, 0, 0}, 10);
    img.legendMarker("destinations", CMapImage::TMarker::Star, {0, 0, 0});
    img.save(out.stage("trace.png"));
}

/** speed_profile.png: speed vs distance, coloured by the limiting reason. */
void writeSpeedProfile(const std::vector<TModeResult>& runs, COutputDir& out) {
    CPlotImage plot;
    plot.setTitle("risknav-explore: speed vs distance travelled");
    plot.setXLabel("distance travelled [m]");
    plot.setYLabel("speed [m/s]");
    for (size_t m = 1; m < runs.size(); m++) {
        std::vector<double> x, y;
        for (const auto& c : runs[m].cycles) {
            x.push_back(c.distance);
            y.push_back(c.commanded);
        }
        plot.addSeries(runs[m].name, x, y, {170, 170, 170}, 1, true);
    }
    if (!runs.empty() && runs.front().fixedIndex < 0) {
        std::set<std::string> labelled;
        const auto& cs = runs.front().cycles;
        for (size_t a = 0; a < cs.size();) {
            size_t b = a;
            while (b + 1 < cs.size() && cs[b + 1].reason == cs[a].reason)
                b++;
            std::vector<double> x, y;
            for (size_t k = a; k <= std::min(b + 1, cs.size() - 1); k++) {
                x.push_back(cs[k].distance);
                y.push_back(cs[k].commanded);
            }
            const std::string label =
                labelled.insert(cs[a].reason).second ? "adaptive: " + cs[a].reason : "";
            plot.addSeries(label, x, y, reasonColour(cs[a].reason), 3);
            a = b + 1;
        }
    }
    plot.save(out.stage("speed_profile.png"));
}

/** snapshots/: the free-space map where the adaptive speed changes (Fig. 16). */
void writeSnapshots(const CExplorer& ex, const std::vector<TModeResult>& runs,
                    COutputDir& out) {
    const auto& o = ex.speed;
    if (!runs.empty() && runs.front().fixedIndex < 0 && !runs.front().snapshots.empty()) {
        for (const auto& s : runs.front().snapshots) {
            const auto& map = s.field.map;
            const auto grid = mapping::toMrptGrid(map);
            CMapImage img(grid, 700);
            const auto& d = s.decision;
            char title[200];
            std::snprintf(title, sizeof(title), "cycle %d: %.2f m/s (%s), d = %s m",
                          s.cycle, d.speed, reasonName(d.reason),
                          std::isfinite(d.dUndecided)
                              ? numberText(std::round(d.dUndecided * 100) / 100).c_str()
                              : "inf");
            img.setTitle(title);
            // obstacles expanded by the fastest speed's margin and the robot
            // size, on the cells of the MRPT grid the image is drawn on, as
            // toMrptGrid() fills them (MRPT snaps its limits to the
            // resolution: a side that is no whole number of cells, 10 m at
            // 3 cm, gets a cell more than the map)
            const auto& clearance = s.field.clearance;
            const int gw = int(grid.getSizeX()), gh = int(grid.getSizeY());
            std::vector<uint8_t> grown(size_t(gw) * gh, 0);
            for (int j = 0; j < gh && j < map.size; j++)
                for (int i = 0; i < gw && i < map.size; i++) {
                    const size_t k = map.index(i, j);
                    grown[size_t(j) * gw + i] =
                        map.cells[k] == mapping::TFusedCell::Free &&
                        clearance[k] < ex.world.robot.radius + o.margins.front();
                }
            img.paintCells(grown, {255, 200, 200});
            for (size_t k = 0; k < d.perSpeed.size(); k++) {
                const TRgb c = kModeColours[(k + 1) % 6];
                img.polyline(d.perSpeed[k].points, c, 1, true);
                const auto& p = d.perSpeed[k];
                img.legendLine(numberText(o.speeds[k]) + " m/s path" +
                                   (p.reached  ? ""
                                    : p.cutOff ? " (longer than the gap rule uses)"
                                               : " (no path)"),
                               c, 1);
            }
            img.polyline(d.path.points, {0, 0, 0}, 3);
            img.legendLine("chosen path", {0, 0, 0}, 3);
            img.marker({s.egoPose.x, s.egoPose.y}, CMapImage::TMarker::Circle,
                       {200, 0, 0}, 10);
            img.marker(d.target, CMapImage::TMarker::Star, {200, 0, 0}, 12);
            img.legendMarker(d.temporaryTarget ? "temporary destination" : "destination",
                             CMapImage::TMarker::Star, {200, 0, 0});
            img.legendLine("grown by robot + fastest margin", {255, 200, 200}, 6);
            char name[64];
            std::snprintf(name, sizeof(name), "snapshots/cycle_%04d.png", s.cycle);
            img.save(out.stage(name));
        }
    }
}
}  // namespace

void writeExploreOutputs(const CExplorer& ex, const std::vector<TModeResult>& runs,
                         COutputDir& out) {
    writeCyclesCsv(ex, runs, out);
    writeTraceImage(ex, runs, out);
    writeSpeedProfile(runs, out);
    writeSnapshots(ex, runs, out);
}

void runExploreApp(const TAppContext& ctx) {
    CExplorer ex;
    ex.loadFromConfigFile(ctx.cfg, ctx.args.seed);
    // (what is in the way of an output refused before the run, not after it)
    COutputDir out(ctx.args.outDir, ctx.info.name,
                   {"cycles.csv", "trace.png", "speed_profile.png", "snapshots/"});
    std::vector<int> modes;
    for (const auto& m : ex.explore.modes) {
        if (m == "adaptive")
            modes.push_back(-1);
        else
            for (size_t k = 0; k < ex.speed.speeds.size(); k++)
                modes.push_back(int(k));
    }
    std::vector<TModeResult> runs;
    for (const int m : modes) {
        CProgress progress(
            m < 0 ? "adaptive" : "fixed " + numberText(ex.speed.speeds[size_t(m)]),
            size_t(ex.explore.duration_max), "s", ctx.args.quiet);
        runs.push_back(ex.runMode(m, [&](double t) { progress.update(size_t(t)); }));
        progress.finish();
    }
    json summary = summaryHeader(ctx, ex.explore.seed);
    summary["necessary_observations"] = ex.necessaryObservations();
    summary["cycle_time_s"] = ex.speed.cycle_time;
    summary["speeds"] = ex.speed.speeds;
    summary["margins"] = ex.speed.margins;
    summary["ego_motion"] = ex.explore.ego_motion;
    // the memory's side as used: memory_size grown to hold the destinations
    summary["memory_size_m"] = ex.memorySize();
    json modesJ = json::array();
    for (const auto& r : runs)
        modesJ.push_back(modeSummary(r, ex.speed));
    summary["modes"] = modesJ;
    // the comparison of the paper (45 s adaptive vs 150 s at the lowest speed)
    const TModeResult* adaptive = nullptr;
    const TModeResult* slowest = nullptr;
    for (const auto& r : runs) {
        if (r.fixedIndex < 0)
            adaptive = &r;
        if (r.fixedIndex == int(ex.speed.speeds.size()) - 1)
            slowest = &r;
    }
    // a ratio of times is the paper's comparison only when both modes reached
    // every destination (of two timeouts it is 1.0 and says nothing): else null
    if (adaptive && slowest)
        summary["adaptive_over_slowest_time"] =
            adaptive->allReached() && slowest->allReached() && slowest->time > 0
                ? json(adaptive->time / slowest->time)
                : json();
    writeExploreOutputs(ex, runs, out);
    json outputs = out.stagedNames();
    mrpt::config::CConfigFileMemory effective;
    ex.saveToConfigFile(effective);
    out.writeText("config_effective.ini", effectiveConfigText(ctx.cfg.path(), effective));
    outputs.push_back("config_effective.ini");
    outputs.push_back("summary.json");
    summary["outputs"] = outputs;
    summary["status"] = adaptive && !adaptive->allReached() ? "incomplete" : "ok";
    out.writeText("summary.json", jsonText(summary));
    out.commit();
    if (!ctx.args.quiet)
        for (const auto& r : runs)
            std::fprintf(stderr, "%s: %-10s %6.1f s, %5.1f m, %d collisions, %s\n",
                         ctx.info.name.c_str(), r.name.c_str(), r.time, r.distance,
                         r.collisions + r.collisionsStatic,
                         r.allReached() ? "all destinations reached" : "NOT all reached");
}
}  // namespace risknav::speed
