#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/CPlotImage.h>
#include <risknav/common/config_read.h>
#include <risknav/common/summary_json.h>
#include <risknav/geometry/polyline.h>
#include <risknav/risk/risk_report.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using nlohmann::json;
using risknav::geometry::polylineLength;

namespace risknav::risk {
namespace {
json finite(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

std::string num(double v) {
    return CCsvWriter::num(v);  // empty where infinite (no obstacle in reach, blocked)
}

void writeCovCsv(const TRiskResult& r, const std::string& path) {
    CCsvWriter csv(path, {"s", "x", "y", "theta", "cov_xx", "cov_xy", "cov_xtheta",
                          "cov_yy", "cov_ytheta", "cov_thetatheta", "d_max", "u",
                          "sensed", "bias_x", "bias_y", "bias_theta"});
    // cov_*: the second moment about the planned pose (TRiskSample::cov);
    // bias_*: the mean pose minus the plan (0 for linear propagation).
    for (const auto& k : r.samples)
        csv.row({num(k.s), num(k.x), num(k.y), num(k.theta), num(k.cov(0, 0)),
                 num(k.cov(0, 1)), num(k.cov(0, 2)), num(k.cov(1, 1)), num(k.cov(1, 2)),
                 num(k.cov(2, 2)), num(k.dmax.d), num(k.u), k.sensedHere ? "1" : "0",
                 num(k.bias[0]), num(k.bias[1]), num(k.bias[2])});
    csv.close();
}

mrpt::math::CMatrixFixed<double, 2, 2> cov2(const Eigen::Matrix3d& c) {
    mrpt::math::CMatrixFixed<double, 2, 2> m;
    m(0, 0) = c(0, 0);
    m(0, 1) = m(1, 0) = c(0, 1);
    m(1, 1) = c(1, 1);
    return m;
}

void drawCommon(CMapImage& img, const CRiskEvaluator& ev) {
    img.marker(ev.options.start, CMapImage::TMarker::Square, {0, 160, 0}, 14, 2);
    img.text({ev.options.start.x + 0.2, ev.options.start.y + 0.2}, "start", {0, 120, 0});
    img.marker(ev.options.goal, CMapImage::TMarker::Star, {0, 0, 0}, 16, 2);
    img.text({ev.options.goal.x + 0.2, ev.options.goal.y + 0.2}, "goal", {0, 0, 0});
    for (const auto& sp : ev.sensingPoints) {
        img.marker({sp.x, sp.y}, CMapImage::TMarker::Triangle, {200, 0, 200}, 14, 2);
        img.text({sp.x + 0.15, sp.y + 0.15}, sp.name, {150, 0, 150});
    }
}

// Standard (D = 1) and maximum (D = D_max) ellipses every `interval` metres
// (Irie et al. Figs. 6-7); the touch points of the maximum ellipses.
void ellipsesImage(const CRiskEvaluator& ev, const CRiskEvaluator::TRow& row,
                   const std::string& title, const std::string& path) {
    CMapImage img(ev.grid());
    img.polyline(row.path, {120, 120, 120}, 2);
    double next = 0;
    for (const auto& k : row.result.samples) {
        if (k.s + 1e-9 < next && !k.sensedHere)
            continue;
        next = k.s + ev.options.ellipse_interval;
        const auto c = cov2(k.cov);
        img.ellipse({k.x, k.y}, c, 1.0, {0, 90, 220}, 1);
        if (std::isfinite(k.dmax.d) && k.dmax.d < 1e4) {
            img.ellipse({k.x, k.y}, c, k.dmax.d, {220, 40, 0}, 1);
            img.marker({k.dmax.touchX, k.dmax.touchY}, CMapImage::TMarker::Cross,
                       {220, 40, 0}, 6, 1);
        }
    }
    drawCommon(img, ev);
    img.legendLine("path", {120, 120, 120}, 2);
    img.legendLine("standard ellipse (D = 1, 39.3 %)", {0, 90, 220}, 1);
    img.legendLine("maximum ellipse (D = D_max)", {220, 40, 0}, 1);
    img.legendMarker("where it touches", CMapImage::TMarker::Cross, {220, 40, 0});
    img.legendMarker("sensing point", CMapImage::TMarker::Triangle, {200, 0, 200});
    img.setTitle(title);
    img.save(path);
}

/** risk_table.csv, and its rows for summary.json. */
json writeRiskTable(const CRiskEvaluator& ev, COutputDir& out) {
    const auto& routes = ev.routes();
    const auto& rows = ev.rows();
    const long best = ev.best();
    CCsvWriter csv(out.stage("risk_table.csv"),
                   {"route", "source", "sensing", "length_m", "U", "u_max", "s_u_max_m",
                    "excluded", "reason", "sensed"});
    json table = json::array();
    for (size_t i = 0; i < rows.size(); i++) {
        const auto& r = rows[i];
        std::string sensed;
        for (const auto& s : r.result.sensed)
            sensed += (sensed.empty() ? "" : "+") + s;
        const bool ok = r.feasible;
        csv.row({routes[r.route].name, routes[r.route].source, ev.sensingName(r),
                 ok ? num(r.result.length) : "", ok ? num(r.result.U) : "",
                 ok ? num(r.result.uMax) : "", ok ? num(r.result.sMaxU) : "",
                 r.excluded ? "true" : "false", r.reason, sensed});
        table.push_back({{"route", routes[r.route].name},
                         {"sensing", ev.sensingName(r)},
                         {"length_m", ok ? finite(r.result.length) : json(nullptr)},
                         {"U", ok ? finite(r.result.U) : json(nullptr)},
                         {"u_max", ok ? finite(r.result.uMax) : json(nullptr)},
                         {"s_u_max_m", ok ? finite(r.result.sMaxU) : json(nullptr)},
                         {"excluded", r.excluded},
                         {"reason", r.reason},
                         {"best", long(i) == best}});
    }
    csv.close();
    return table;
}

/** The routes and sensing points, for summary.json. */
void addRoutesJson(const CRiskEvaluator& ev, json& j) {
    const auto& routes = ev.routes();
    json jr = json::array();
    for (const auto& r : routes) {
        json w = json::array();
        for (const auto& p : r.waypoints)
            w.push_back({p.x, p.y});
        jr.push_back({{"name", r.name},
                      {"source", r.source},
                      {"length_m", polylineLength(r.waypoints)},
                      {"waypoints", w}});
    }
    j["routes"] = jr;
    json sp = json::array();
    for (const auto& p : ev.sensingPoints)
        sp.push_back({{"name", p.name}, {"x", p.x}, {"y", p.y}, {"radius", p.radius}});
    j["sensing_points"] = sp;
}

// Covariance tables: the plain row and the best row of each route (the
// rows that kept their samples, CRiskEvaluator::TRow::result).
void writeCovTables(const CRiskEvaluator& ev, COutputDir& out) {
    const auto& routes = ev.routes();
    const auto& rows = ev.rows();
    for (const auto& r : rows)
        if (r.feasible && !r.result.samples.empty()) {
            std::vector<std::string> visited;
            for (size_t i : r.sensing)
                visited.push_back(ev.sensingPoints[i].name);
            writeCovCsv(r.result, out.stage(CRiskEvaluator::covFileName(
                                      routes[r.route].name, visited)));
        }
}

// paths.png: every candidate, labelled; the best thick.
void writePathsImage(const CRiskEvaluator& ev, COutputDir& out) {
    const auto& routes = ev.routes();
    const auto& rows = ev.rows();
    const long best = ev.best();
    CMapImage img(ev.grid());
    if (ev.gvg()) {
        img.paintCells(ev.gvg()->skeleton(), {235, 200, 90});
        img.legendLine("GVG", {235, 200, 90}, 2);
    }
    for (size_t r = 0; r < routes.size(); r++) {
        const bool isBest = best >= 0 && rows[size_t(best)].route == r;
        const TRgb c = seriesColour(r);
        img.polyline(routes[r].waypoints, c, isBest ? 5 : 2,
                     routes[r].source != "config" && !isBest);
        // Labels at different fractions of the routes' lengths, so they do
        // not sit on each other.
        const auto& w = routes[r].waypoints;
        double want = (0.3 + 0.12 * double(r % 4)) * polylineLength(w), acc = 0;
        TPoint2D mid = w.front();
        for (size_t i = 1; i < w.size(); i++) {
            const double L = std::hypot(w[i].x - w[i - 1].x, w[i].y - w[i - 1].y);
            if (acc + L >= want && L > 0) {
                const double f = (want - acc) / L;
                mid = {w[i - 1].x + f * (w[i].x - w[i - 1].x),
                       w[i - 1].y + f * (w[i].y - w[i - 1].y)};
                break;
            }
            acc += L;
        }
        char label[96];
        const auto& plain = ev.plainRow(r);
        std::snprintf(label, sizeof(label), "%s: U=%.2f", routes[r].name.c_str(),
                      plain.result.U);
        img.text({mid.x + 0.15, mid.y + 0.15}, label, c, 0.5);
        img.legendLine(routes[r].name +
                           (routes[r].source == "gvg"    ? " (GVG)"
                            : routes[r].source == "grid" ? " (grid)"
                                                         : "") +
                           (isBest ? " - best" : ""),
                       c, isBest ? 5 : 2);
    }
    if (best >= 0 && !rows[size_t(best)].sensing.empty())
        img.polyline(rows[size_t(best)].path, {0, 0, 0}, 1, true);
    drawCommon(img, ev);
    char title[256];
    if (best >= 0)
        std::snprintf(title, sizeof(title),
                      "risknav-risk-eval: %zu routes | best %s with sensing %s, U = %.2f",
                      routes.size(), routes[rows[size_t(best)].route].name.c_str(),
                      ev.sensingName(rows[size_t(best)]).c_str(),
                      rows[size_t(best)].result.U);
    else
        std::snprintf(title, sizeof(title), "risknav-risk-eval: %s",
                      routes.empty() ? "no route" : "all routes excluded");
    img.setTitle(title);
    img.save(out.stage("paths.png"));
}

// Ellipses per route (no sensing) and for the best row.
void writeEllipsesImages(const CRiskEvaluator& ev, COutputDir& out) {
    const auto& routes = ev.routes();
    const auto& rows = ev.rows();
    const long best = ev.best();
    for (size_t r = 0; r < routes.size(); r++) {
        const auto& plain = ev.plainRow(r);
        if (!plain.feasible)
            continue;
        char title[160];
        std::snprintf(title, sizeof(title),
                      "route %s, no sensing: U = %.2f, max u = %.2f, %.1f m",
                      routes[r].name.c_str(), plain.result.U, plain.result.uMax,
                      plain.result.length);
        ellipsesImage(ev, plain, title,
                      out.stage(CRiskEvaluator::ellipsesFileName(routes[r].name)));
    }
    if (best >= 0) {
        const auto& b = rows[size_t(best)];
        char title[160];
        std::snprintf(title, sizeof(title),
                      "best: route %s, sensing %s: U = %.2f, max u = %.2f",
                      routes[b.route].name.c_str(), ev.sensingName(b).c_str(), b.result.U,
                      b.result.uMax);
        ellipsesImage(ev, b, title, out.stage("ellipses_best.png"));
    }
}

// u along the arc length.
void writeRiskProfileImage(const CRiskEvaluator& ev, COutputDir& out) {
    const auto& routes = ev.routes();
    const auto& rows = ev.rows();
    const long best = ev.best();
    CPlotImage plot;
    plot.setLogY(true);
    plot.setXLabel("arc length s [m]");
    plot.setYLabel("u = 1 / D_max^2");
    for (size_t r = 0; r < routes.size(); r++) {
        const auto& plain = ev.plainRow(r);
        if (!plain.feasible)
            continue;
        std::vector<double> s, u;
        for (const auto& k : plain.result.samples) {
            s.push_back(k.s);
            u.push_back(k.u);
        }
        plot.addSeries(routes[r].name + " (U=" + CCsvWriter::num(plain.result.U, 4) + ")",
                       s, u, seriesColour(r), 2);
    }
    if (best >= 0 && !rows[size_t(best)].sensing.empty()) {
        const auto& b = rows[size_t(best)];
        std::vector<double> s, u;
        for (const auto& k : b.result.samples) {
            s.push_back(k.s);
            u.push_back(k.u);
            if (k.sensedHere)
                plot.addVLine(k.s, "sensing", {200, 0, 200});
        }
        plot.addSeries("best: " + routes[b.route].name + " + " + ev.sensingName(b) +
                           " (U=" + CCsvWriter::num(b.result.U, 4) + ")",
                       s, u, {0, 0, 0}, 1, true);
    }
    plot.setTitle(
        "risk density along each route (log scale); U = integral of u ds, eq. (30)");
    plot.save(out.stage("risk_profile.png"));
}

/** The models, parameters, work done and map, for summary.json. */
void addParametersJson(const CRiskEvaluator& ev, json& j) {
    const auto& rows = ev.rows();
    const TRiskOptions o = ev.riskOptions();
    const auto& rule = ev.options.obstacles;
    j["error_model"] = ev.odometry.error_model;
    j["propagation"] = ev.propagation.propagation;
    j["work"] = {{"rows", rows.size()},
                 {"propagation_steps", ev.propagationSteps()},
                 {"trajectories_per_step", ev.trajectoriesPerStep()},
                 {"trajectory_steps", ev.trajectorySteps()},
                 {"limits",
                  {{"routes", CRiskEvaluator::kMaxRoutes},
                   {"rows", CRiskEvaluator::kMaxRows},
                   {"propagation_steps", CRiskEvaluator::kMaxSteps},
                   {"trajectory_steps", CRiskEvaluator::kMaxTrajectorySteps}}}};
    j["parameters"] = {{"propagation", ev.propagation.propagation},
                       {"samples", ev.propagation.samples},
                       {"wheel_radius_l", o.odometry.radiusL},
                       {"wheel_radius_r", o.odometry.radiusR},
                       {"tread", o.odometry.tread},
                       {"sigma_wheel_radius_l", o.odometry.sigmaRL},
                       {"sigma_wheel_radius_r", o.odometry.sigmaRR},
                       {"sigma_tread", o.odometry.sigmaT},
                       {"tau", o.tau},
                       {"speed", o.speed},
                       {"turn_rate_deg", o.turnRate * 180 / M_PI},
                       {"init_sigma",
                        {std::sqrt(o.sigmaP0(0, 0)), std::sqrt(o.sigmaP0(1, 1)),
                         std::sqrt(o.sigmaP0(2, 2))}},
                       {"eval_step", o.evalStep},
                       {"robot_radius", ev.robot.radius},
                       {"occupied_threshold", rule.occupied_threshold},
                       {"free_threshold", rule.free_threshold},
                       {"unknown_is_obstacle", rule.unknown_is_obstacle},
                       {"outside_is_obstacle", rule.outside_is_obstacle},
                       {"u_threshold", ev.options.u_threshold}};
    j["map"] = {{"file", ev.options.map.map_file},
                {"size_x", ev.grid().getSizeX()},
                {"size_y", ev.grid().getSizeY()},
                {"resolution", ev.grid().getResolution()},
                {"obstacle_cells_grown", ev.field().obstacleCount()}};
    j["gvg_cells"] = ev.gvg() ? ev.gvg()->skeletonCells() : 0;
}
}  // namespace

json writeRiskReport(const CRiskEvaluator& ev, COutputDir& out) {
    const auto& routes = ev.routes();
    const auto& rows = ev.rows();
    const long best = ev.best();
    json j;
    j["status"] = routes.empty() ? "no route" : (best < 0 ? "all excluded" : "ok");
    // why the grid has no way for the robot disc (null: it has one, or
    // grid_routes = 0)
    if (ev.noWayFailure().empty())
        j["no_way"] = nullptr;
    else
        j["no_way"] = {{"failure", ev.noWayFailure()}, {"reason", ev.noWayReason()}};

    j["table"] = writeRiskTable(ev, out);
    if (best >= 0) {
        const auto& b = rows[size_t(best)];
        j["best"] = {{"route", routes[b.route].name},
                     {"sensing", ev.sensingName(b)},
                     {"U", b.result.U},
                     {"u_max", b.result.uMax},
                     {"length_m", b.result.length}};
    } else
        j["best"] = nullptr;
    addRoutesJson(ev, j);
    writeCovTables(ev, out);
    writePathsImage(ev, out);
    writeEllipsesImages(ev, out);
    writeRiskProfileImage(ev, out);
    addParametersJson(ev, j);
    return j;
}

void runRiskEvalApp(const TAppContext& ctx) {
    const auto t0 = std::chrono::steady_clock::now();
    CRiskEvaluator ev;
    ev.loadFromConfigFile(ctx.cfg);
    if (ctx.args.seed)
        ev.options.seed = *ctx.args.seed;
    COutputDir out(ctx.args.outDir,
                   ctx.info.name);  // checked (and locked) before the work
    ev.checkOutputPaths(ctx.cfg, out.dir());
    ev.evaluate();
    json summary = summaryHeader(ctx, ev.options.seed);
    summary.update(writeRiskReport(ev, out));
    summary["timing"] = {
        {"wall_time_s",
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}};
    mrpt::config::CConfigFileMemory effective;
    ev.saveToConfigFile(effective);
    commitRun(ctx, out, summary, effective);
    if (!ctx.args.quiet) {
        if (ev.best() >= 0) {
            const auto& b = ev.rows()[size_t(ev.best())];
            std::fprintf(stderr,
                         "%s: %zu routes x sensing subsets = %zu rows; best %s with "
                         "sensing %s, U = %.3f -> %s\n",
                         ctx.info.name.c_str(), ev.routes().size(), ev.rows().size(),
                         ev.routes()[b.route].name.c_str(), ev.sensingName(b).c_str(),
                         b.result.U, out.dir().c_str());
        } else
            std::fprintf(stderr, "%s: %s%s%s -> %s\n", ctx.info.name.c_str(),
                         summary["status"].get<std::string>().c_str(),
                         ev.noWayReason().empty() ? "" : ": ", ev.noWayReason().c_str(),
                         out.dir().c_str());
    }
}

}  // namespace risknav::risk
