#include <risknav/afraid/afraid_report.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/CPlotImage.h>
#include <risknav/common/summary_json.h>

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using nlohmann::json;

namespace risknav::afraid {
namespace {
std::string num(double v) {
    return std::isfinite(v) ? CCsvWriter::num(v) : "";
}
json finite(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

// The principal axis of the trajectory: the "along the corridor" axis of the
// paper's Figs. 8-9 (exact for a corridor, an approximation for other routes).
void principalAxis(const std::vector<TPoint2D>& t, double& mx, double& my, double& ux,
                   double& uy) {
    mx = my = 0;
    for (const auto& p : t) {
        mx += p.x / t.size();
        my += p.y / t.size();
    }
    double sxx = 0, syy = 0, sxy = 0;
    for (const auto& p : t) {
        sxx += (p.x - mx) * (p.x - mx);
        syy += (p.y - my) * (p.y - my);
        sxy += (p.x - mx) * (p.y - my);
    }
    const double a = 0.5 * std::atan2(2 * sxy, sxx - syy);
    ux = std::cos(a);
    uy = std::sin(a);
    if (ux < 0 || (ux == 0 && uy < 0)) {
        ux = -ux;
        uy = -uy;
    }
}
}  // namespace

json writeAfraidReport(const CAfraidLearner& l, COutputDir& out) {
    const auto& g = l.grid();
    const auto& lvl = l.level();
    const int sx = g.sizeX(), sy = g.sizeY();
    json j;

    // The learned experience. After a partial replay under another name, so
    // that a complete earlier file of the same name is never replaced by it.
    std::string afraidFile = l.afraidName;
    if (l.partial())
        afraidFile = afraidFile.substr(0, afraidFile.size() - 7) + ".partial.afraid";
    g.save(out.stage(afraidFile));

    // events.csv
    {
        CCsvWriter csv(
            out.stage("events.csv"),
            {"t", "rawlog", "entry", "robot_x", "robot_y", "robot_phi", "obstacle_x",
             "obstacle_y", "diff", "obs_cur", "obs_predict", "speed"});
        for (const auto& e : l.events())
            csv.row({CCsvWriter::fixed(e.t, 3), e.rawlog, std::to_string(e.entry),
                     num(e.robotX), num(e.robotY), num(e.robotPhi),
                     e.obstacleFound ? num(e.obstacleX) : "",
                     e.obstacleFound ? num(e.obstacleY) : "", num(e.diff),
                     std::to_string(e.obsCur), std::to_string(e.obsPredict),
                     num(e.speed)});
        csv.close();
    }
    // trajectory.csv: the localization of every frame.
    {
        CCsvWriter csv(out.stage("trajectory.csv"),
                       {"t", "x", "y", "phi", "cov_xx", "cov_yy", "particles",
                        "scan_map_agreement", "localized"});
        for (const auto& e : l.estimates())
            csv.row({CCsvWriter::fixed(e.t, 3), num(e.x), num(e.y), num(e.phi),
                     num(e.covXX), num(e.covYY), std::to_string(e.particles),
                     num(e.agreement), e.localized ? "1" : "0"});
        csv.close();
    }
    // zones.csv
    json zones = json::array();
    {
        CCsvWriter csv(out.stage("zones.csv"),
                       {"zone", "x_min", "x_max", "y_min", "y_max", "area_m2",
                        "peak_level", "robot_events", "obstacle_events"});
        for (const auto& z : l.zones()) {
            csv.row({std::to_string(z.id), num(z.xMin), num(z.xMax), num(z.yMin),
                     num(z.yMax), num(z.area), num(z.peak), std::to_string(z.robotEvents),
                     std::to_string(z.obstacleEvents)});
            zones.push_back({{"id", z.id},
                             {"x_min", z.xMin},
                             {"x_max", z.xMax},
                             {"y_min", z.yMin},
                             {"y_max", z.yMax},
                             {"area_m2", z.area},
                             {"peak_level", z.peak},
                             {"robot_events", z.robotEvents},
                             {"obstacle_events", z.obstacleEvents}});
        }
        csv.close();
    }
    // Nav2 Speed Filter mask (percent): occupancy p = 100 - speed percent in
    // the zones, 0 (no limit) elsewhere; "scale" mode, so pixel = 255 (1 - p/100).
    {
        const int pct = int(std::lround(100.0 * l.vSafe / l.vMax));
        std::vector<uint8_t> pix(size_t(sx) * sy, 255);
        for (const auto& z : l.zones())
            for (int k : z.mask) {
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
    double peak = 0;
    for (float v : lvl)
        peak = std::max(peak, double(v));
    {
        CMapImage img(l.map());
        img.heatOverlay(lvl, 0.f, float(std::max(peak, l.zoneThreshold * 2)),
                        "afraid level", 0.65, float(0.25 * l.zoneThreshold));
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
            img.text({z.xMin, z.yMax + 0.15}, "zone " + std::to_string(z.id),
                     {150, 0, 150});
        }
        img.legendLine("robot path (MCL)", {150, 150, 150}, 1);
        img.legendMarker("robot at an event", CMapImage::TMarker::Circle, {0, 0, 0});
        img.legendMarker("unexpected obstacle", CMapImage::TMarker::Circle, {220, 0, 0});
        img.legendLine("zone (level > " + CCsvWriter::num(l.zoneThreshold, 3) + ")",
                       {200, 0, 200}, 2);
        char title[200];
        std::snprintf(title, sizeof(title),
                      "risknav-afraid-learn: %zu new events (%llu in all), %zu zones%s",
                      l.events().size(),
                      static_cast<unsigned long long>(g.totalRobotEvents()),
                      l.zones().size(), l.partial() ? "  [PARTIAL]" : "");
        img.setTitle(title);
        img.save(out.stage("afraid.png"));
    }
    // profile.png: events per 10 cm and the level along the route's principal axis.
    json axis = nullptr;
    if (l.trajectory().size() > 2) {
        double mx, my, ux, uy;
        principalAxis(l.trajectory(), mx, my, ux, uy);
        double lo = 1e18, hi = -1e18;
        for (const auto& p : l.trajectory()) {
            const double s = (p.x - mx) * ux + (p.y - my) * uy;
            lo = std::min(lo, s);
            hi = std::max(hi, s);
        }
        const double bin = 0.1;
        const int nb = std::max(1, int(std::ceil((hi - lo) / bin)) + 1);
        std::vector<double> xs(static_cast<size_t>(nb)),
            counts(static_cast<size_t>(nb), 0.0), level(static_cast<size_t>(nb), 0.0);
        for (int b = 0; b < nb; b++)
            xs[size_t(b)] = lo + (b + 0.5) * bin;
        auto binOf = [&](double x, double y) {
            return std::clamp(int(std::floor(((x - mx) * ux + (y - my) * uy - lo) / bin)),
                              0, nb - 1);
        };
        for (const auto& e : l.events())
            counts[size_t(binOf(e.robotX, e.robotY))] += 1;
        for (const auto& p : l.trajectory()) {
            const auto b = size_t(binOf(p.x, p.y));
            level[b] = std::max(level[b], l.levelAt(p.x, p.y));
        }
        double cmax = 1;
        for (double c : counts)
            cmax = std::max(cmax, c);
        std::vector<double> scaled(level.size());
        for (size_t i = 0; i < level.size(); i++)
            scaled[i] = level[i] / std::max(peak, 1e-9) * cmax;
        // Positions are world coordinates projected on the axis (for a corridor
        // along x: x itself, so door positions compare directly).
        const double o = mx * ux + my * uy;
        std::vector<double> pos(xs.size());
        for (size_t i = 0; i < xs.size(); i++)
            pos[i] = xs[i] + o;
        CPlotImage plot;
        plot.setXLabel(
            "position along the route's main axis (world coordinates projected) [m]");
        plot.setYLabel("events per 10 cm");
        plot.addSeries("afraid events (robot position), per 10 cm", pos, counts,
                       {40, 40, 40}, 1);
        plot.addSeries("generalized level (scaled to the event maximum)", pos, scaled,
                       {220, 40, 0}, 2);
        for (const auto& z : l.zones()) {
            const double a = z.xMin * ux + z.yMin * uy, b = z.xMax * ux + z.yMax * uy;
            plot.addVLine(std::min(a, b), "zone " + std::to_string(z.id), {200, 0, 200});
            plot.addVLine(std::max(a, b), "", {200, 0, 200});
        }
        plot.setTitle(
            "afraid events and the learned level along the route (cf. Choi et al. Figs. "
            "8-9)");
        plot.save(out.stage("profile.png"));
        axis = {{"direction", {ux, uy}}, {"from_m", pos.front()}, {"to_m", pos.back()}};

        // The speed limit along the axis (eqs. 13-14 with the look-ahead),
        // driving towards +axis, and the paper's 10 m comparison: the time for
        // 10 m starting 1 m before the first zone, at the learning speed
        // (v_safe everywhere, "before learning") and with the limit ("after").
        auto levelFn = [&](double x, double y) { return l.levelAt(x, y); };
        const auto& d = l.detector.options;
        std::vector<double> vs(pos.size());
        for (size_t i = 0; i < pos.size(); i++) {
            const double s0 = pos[i] - o;
            const TPoint2D p0(mx + s0 * ux, my + s0 * uy),
                p1(mx + (s0 + 5) * ux, my + (s0 + 5) * uy);
            vs[i] = afraidSpeedLimit(levelFn, {p0, p1}, l.vMax, l.vMax, l.vSafe,
                                     l.zoneThreshold, d.t_delay, d.decel);
        }
        CPlotImage sp;
        sp.setXLabel(
            "position along the route's main axis (world coordinates projected) [m]");
        sp.setYLabel("speed [m/s]");
        sp.addSeries("v = min(v_behaviour, v_afraid), driving towards +axis", pos, vs,
                     {0, 90, 200}, 2);
        std::vector<double> safe(pos.size(), l.vSafe);
        sp.addSeries("before learning: v_safe everywhere", pos, safe, {120, 120, 120}, 1,
                     true);
        for (const auto& z : l.zones()) {
            const double a = z.xMin * ux + z.yMin * uy, b = z.xMax * ux + z.yMax * uy;
            sp.addVLine(std::min(a, b), "zone " + std::to_string(z.id), {200, 0, 200});
            sp.addVLine(std::max(a, b), "", {200, 0, 200});
        }
        double firstZone = 1e18;
        for (const auto& z : l.zones())
            firstZone = std::min(firstZone, std::min(z.xMin * ux + z.yMin * uy,
                                                     z.xMax * ux + z.yMax * uy));
        if (!l.zones().empty() && pos.size() > 1) {
            const double s0 = std::max(pos.front(), firstZone - 1.0), s1 = s0 + 10.0;
            double tAfter = 0;
            for (size_t i = 1; i < pos.size(); i++)
                if (pos[i] > s0 && pos[i] <= s1)
                    tAfter += (pos[i] - pos[i - 1]) / vs[i];
            const double span = std::min(s1, pos.back()) - s0;
            j["ten_metre_section"] = {
                {"from_m", s0},
                {"to_m", s0 + span},
                {"time_before_s", span / l.vSafe},
                {"time_after_s", tAfter},
                {"mean_speed_after", tAfter > 0 ? span / tAfter : 0.0}};
            char t[200];
            std::snprintf(t, sizeof(t),
                          "speed limit along the route: %.1f m from %.1f m in %.1f s "
                          "(%.1f s at v_safe)",
                          span, s0, tAfter, span / l.vSafe);
            sp.setTitle(t);
        } else
            sp.setTitle("speed limit along the route (no zone: v_max everywhere)");
        sp.save(out.stage("speed.png"));
    }

    if (!j.contains("ten_metre_section"))
        j["ten_metre_section"] = nullptr;
    j["status"] = l.partial() ? "partial" : (l.diverged() ? "diverged" : "ok");
    j["partial"] = l.partial();
    j["error"] = l.error();
    j["rawlogs"] = l.rawlogs;
    j["frames"] = l.frames();
    j["localization"] = {
        {"localized_frames", l.localizedFrames()},
        {"localized_fraction",
         l.frames() ? double(l.localizedFrames()) / l.frames() : 0.0},
        {"mean_scan_map_agreement", l.meanMatch()},
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
    j["afraid_in"] = l.afraidIn;
    j["zones"] = zones;
    j["peak_level"] = peak;
    j["profile_axis"] = axis;
    j["parameters"] = {{"kernel_bandwidth", l.krr.bandwidth},
                       {"kernel_lambda", l.krr.lambda},
                       {"zone_threshold", l.zoneThreshold},
                       {"v_max", l.vMax},
                       {"v_safe", l.vSafe},
                       {"t_delay", l.detector.options.t_delay},
                       {"decel", l.detector.options.decel},
                       {"beta", l.detector.options.beta},
                       {"half_width", l.detector.options.half_width},
                       {"foot_step", l.detector.options.foot_step},
                       {"diff_threshold", l.detector.options.diff_threshold}};
    return j;
}

void runAfraidLearnApp(const TAppContext& ctx) {
    const auto t0 = std::chrono::steady_clock::now();
    CAfraidLearner l;
    l.loadFromConfigFile(ctx.cfg, ctx.args.extra, ctx.args.seed);
    l.run(ctx.args.quiet);
    l.generalize();
    COutputDir out(ctx.args.outDir);
    json summary = summaryHeader(ctx, l.seed);
    summary.update(writeAfraidReport(l, out));
    out.writeText("config_effective.ini", ctx.cfg.effectiveConfigText());
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    summary["timing"] = {
        {"wall_time_s", wall},
        {"replay_s", l.replaySeconds()},
        {"frames_per_s", l.replaySeconds() > 0 ? l.frames() / l.replaySeconds() : 0.0}};
    summary["outputs"] = out.stagedNames();
    summary["outputs"].push_back("summary.json");
    out.writeText("summary.json", jsonText(summary));
    out.commit();
    if (l.partial())  // results up to the bad entry are saved, marked partial
        throw CBadInputError(l.error() + "; partial results in " + out.dir());
    if (!ctx.args.quiet)
        std::fprintf(stderr, "%s: %zu frames, %zu events, %zu zones%s -> %s\n",
                     ctx.info.name.c_str(), l.frames(), l.events().size(),
                     l.zones().size(), l.diverged() ? " (LOCALIZATION DIVERGED)" : "",
                     out.dir().c_str());
}

}  // namespace risknav::afraid
