#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/config_read.h>
#include <risknav/common/summary_json.h>
#include <risknav/viewpoint/viewpoint_report.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using nlohmann::json;

namespace risknav::viewpoint {
namespace {
std::string num(double v) {
    return std::isfinite(v) ? CCsvWriter::num(v) : "inf";
}
json finite(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}
double deg(double rad) {
    return rad * 180 / M_PI;
}
char letter(TStrategy s) {
    return char(s);
}

std::string landmarkList(const TObservation& o, const std::vector<TLandmark>& lms) {
    std::string s;
    for (int k = 0; k < o.landmarkCount(); k++)
        s += (k ? "+" : "") + lms[size_t(o.lm[size_t(k)])].id;
    return s;
}

const TPlanRow* optimalRow(const CViewpointPlanner& p) {
    const auto o = p.optimal();
    return o ? &p.sweep()[o->first].rows[o->second] : nullptr;
}

// The world as a raster for CMapImage: obstacles black, free white.
mrpt::maps::COccupancyGridMap2D worldRaster(const TPolygonWorld& w, double res,
                                            cv::Mat& obstacleMask) {
    mrpt::maps::COccupancyGridMap2D g(float(w.xMin), float(w.xMax), float(w.yMin),
                                      float(w.yMax), float(res));
    const int nx = int(g.getSizeX()), ny = int(g.getSizeY());
    obstacleMask = cv::Mat(ny, nx, CV_8UC1, cv::Scalar(0));
    auto toCells = [&](const std::vector<TPoint2D>& r) {
        std::vector<cv::Point> pts;
        for (const auto& p : r)
            pts.emplace_back(int(std::lround((p.x - g.getXMin()) / res - 0.5)),
                             int(std::lround((p.y - g.getYMin()) / res - 0.5)));
        return pts;
    };
    // Each obstacle (outer ring minus its holes) on its own, then OR-ed in:
    // a hole must not clear another obstacle inside it.
    for (const auto& o : w.obstacles) {
        const auto outer = toCells(o.outer);
        const cv::Rect box = cv::boundingRect(outer) & cv::Rect(0, 0, nx, ny);
        if (box.empty())
            continue;
        auto shifted = [&](std::vector<cv::Point> pts) {
            for (auto& q : pts)
                q -= box.tl();
            return std::vector<std::vector<cv::Point>>{pts};
        };
        cv::Mat one(box.size(), CV_8UC1, cv::Scalar(0));
        cv::fillPoly(one, shifted(outer), cv::Scalar(255));
        for (const auto& h : o.holes)
            cv::fillPoly(one, shifted(toCells(h)), cv::Scalar(0));
        cv::Mat roi = obstacleMask(box);
        cv::bitwise_or(roi, one, roi);
    }
    for (int cy = 0; cy < ny; cy++)
        for (int cx = 0; cx < nx; cx++)
            g.setCell(cx, cy, obstacleMask.at<uint8_t>(cy, cx) ? 0.0f : 1.0f);
    return g;
}

void drawPlan(const CViewpointPlanner& p, const std::string& path) {
    const TPolygonWorld& w = p.world();
    const double span = std::max(w.xMax - w.xMin, w.yMax - w.yMin);
    // About 1200 cells on the longer side, whatever the world's size.
    const double res = std::max(span / 1200, 0.002);
    cv::Mat obst;
    const auto grid = worldRaster(w, res, obst);
    CMapImage img(grid, 1400);
    const TPlanRow* row = optimalRow(p);
    const size_t sweepIdx = p.optimal() ? p.optimal()->first : 0;
    const double S = p.sweep().empty() ? 0 : p.sweep()[sweepIdx].S;
    // C-obstacles of the shown S: cells nearer an obstacle than R + S.
    {
        cv::Mat freeMask;
        cv::bitwise_not(obst, freeMask);
        cv::Mat dist;
        cv::distanceTransform(freeMask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
        const double Ds = p.robot.radius + S;
        std::vector<uint8_t> mask(size_t(obst.cols) * size_t(obst.rows), 0);
        for (int cy = 0; cy < obst.rows; cy++)
            for (int cx = 0; cx < obst.cols; cx++) {
                const bool edge =
                    cx == 0 || cy == 0 || cx == obst.cols - 1 || cy == obst.rows - 1;
                const double d = std::min(double(dist.at<float>(cy, cx)) * res,
                                          std::min({(cx + 0.5) * res, (cy + 0.5) * res,
                                                    (obst.cols - cx - 0.5) * res,
                                                    (obst.rows - cy - 0.5) * res}));
                if (!obst.at<uint8_t>(cy, cx) && (d < Ds || edge))
                    mask[size_t(cy) * size_t(obst.cols) + size_t(cx)] = 1;
            }
        img.paintCells(mask, {255, 215, 170});
    }
    for (const auto& o : w.obstacles) {
        auto ring = o.outer;
        ring.push_back(ring.front());
        img.polyline(ring, {0, 0, 0}, 1);
    }
    if (!p.sweep().empty())
        for (const auto& e : p.sweep()[sweepIdx].graphEdges)
            img.segment(e.a, e.b, {190, 190, 225}, 1);
    // Landmarks: a bar along the wall and a tick along the facing.
    for (const auto& l : w.landmarks) {
        const auto [a, b] = landmarkEnds(l);
        const double k = std::max(l.radius, 0.012 * span);
        const TPoint2D ea{l.x + (a.x - l.x) * k / l.radius,
                          l.y + (a.y - l.y) * k / l.radius};
        const TPoint2D eb{l.x + (b.x - l.x) * k / l.radius,
                          l.y + (b.y - l.y) * k / l.radius};
        img.segment(ea, eb, {0, 140, 0}, 3);
        img.segment({l.x, l.y},
                    {l.x + k * std::cos(l.facing), l.y + k * std::sin(l.facing)},
                    {0, 140, 0}, 1);
        img.text({l.x + 1.5 * k * std::cos(l.facing), l.y + 1.5 * k * std::sin(l.facing)},
                 l.id, {0, 110, 0}, 0.35);
    }
    const TCameraRig rig = p.camera.rig();
    const double halfFov = std::atan(rig.width / 2.0 / rig.focal);
    if (row) {
        img.polyline(row->path, {200, 30, 30}, 3);
        for (size_t v = 0; v < row->viewpoints.size(); v++) {
            const auto& vp = row->viewpoints[v];
            if (!vp.eval.best)
                continue;
            const auto& ch = *vp.eval.best;
            const mrpt::math::TPose2D pose{vp.at.x, vp.at.y, vp.at.heading};
            // Camera fans: each camera's field of view toward its landmarks.
            for (int side : {+1, -1}) {
                const TPoint2D c = cameraCentre(pose, side, rig.b_r);
                const double psi = pose.phi + ch.obs.pan[side > 0 ? 0 : 1];
                double len = 0;
                for (int k = 0; k < ch.obs.landmarkCount(); k++) {
                    const auto& l = w.landmarks[size_t(ch.obs.lm[size_t(k)])];
                    len = std::max(len, std::hypot(l.x - c.x, l.y - c.y));
                }
                const TRgb fc = side > 0 ? TRgb{30, 90, 230} : TRgb{150, 40, 200};
                for (const double a : {psi - halfFov, psi + halfFov})
                    img.segment(c, {c.x + len * std::cos(a), c.y + len * std::sin(a)}, fc,
                                1);
            }
            img.circle({vp.at.x, vp.at.y}, p.robot.radius * 0.35, {200, 30, 30}, 2);
            char label[96];
            std::snprintf(label, sizeof(label), "%zu%c %s", v + 1,
                          letter(ch.obs.strategy),
                          landmarkList(ch.obs, w.landmarks).c_str());
            img.text({vp.at.x + 0.6 * p.robot.radius, vp.at.y - 0.6 * p.robot.radius},
                     label, {120, 0, 0}, 0.4);
        }
    }
    const TPoint2D start = p.options.start, goal = p.options.goal;
    img.marker(start, CMapImage::TMarker::Square, {0, 150, 0}, 14, 2);
    img.text({start.x + 0.1, start.y + 0.1}, "start", {0, 110, 0});
    img.marker(goal, CMapImage::TMarker::Star, {0, 0, 0}, 16, 2);
    img.text({goal.x + 0.1, goal.y + 0.1}, "goal", {0, 0, 0});
    img.legendLine("C-obstacle (R + S)", {255, 215, 170}, 6);
    img.legendLine("visibility graph", {190, 190, 225}, 1);
    img.legendLine("optimal path", {200, 30, 30}, 3);
    img.legendMarker("viewpoint: number, strategy, landmarks", CMapImage::TMarker::Circle,
                     {200, 30, 30});
    img.legendLine("left camera field of view", {30, 90, 230}, 1);
    img.legendLine("right camera field of view", {150, 40, 200}, 1);
    img.legendLine("landmark (tick: facing)", {0, 140, 0}, 3);
    char title[256];
    if (row)
        std::snprintf(
            title, sizeof(title),
            "risknav-viewpoint-plan: optimal S = %.0f mm, route %d, %.0f mm, %zu "
            "viewpoints",
            row->S * 1000, row->route, row->length * 1000, row->viewpoints.size());
    else
        std::snprintf(
            title, sizeof(title),
            "risknav-viewpoint-plan: no feasible plan (graph of S = %.0f mm shown)",
            S * 1000);
    img.setTitle(title);
    img.save(path);
}

// Per S: the path the paper's tables list (the same ranking within one S).
const TPlanRow* bestOfS(const TSweepPoint& sp, double tol) {
    std::vector<const TPlanRow*> rows;
    for (const auto& r : sp.rows)
        rows.push_back(&r);
    return bestPlan(rows, tol);
}

// sweep.csv: every (S, path); its rows for summary.json.
json writeSweepCsv(const CViewpointPlanner& p, const TPlanRow* opt, COutputDir& out) {
    CCsvWriter csv(
        out.stage("sweep.csv"),
        {"S_m", "path", "route", "length_m", "viewpoints", "feasible", "fail_at_m",
         "min_allowed_error_m", "strategy_A", "strategy_B", "strategy_C", "optimal"});
    json sweep = json::array();
    for (size_t k = 0; k < p.sweep().size(); k++) {
        const auto& sp = p.sweep()[k];
        json paths = json::array();
        for (size_t r = 0; r < sp.rows.size(); r++) {
            const auto& row = sp.rows[r];
            size_t cnt[3] = {0, 0, 0};
            for (const auto& vp : row.viewpoints)
                if (vp.eval.best)
                    cnt[size_t(vp.eval.best->obs.strategy) - size_t('A')]++;
            const bool isOpt = opt == &row;
            csv.row({num(sp.S), std::to_string(r + 1), std::to_string(row.route),
                     num(row.length),
                     row.feasible ? std::to_string(row.viewpoints.size()) : "",
                     row.feasible ? "true" : "false", row.feasible ? "" : num(row.reach),
                     num(row.minAllowed), std::to_string(cnt[0]), std::to_string(cnt[1]),
                     std::to_string(cnt[2]), isOpt ? "true" : "false"});
            json verts = json::array();
            for (const auto& q : row.path)
                verts.push_back({q.x, q.y});
            paths.push_back(
                {{"path", r + 1},
                 {"vertices", verts},
                 {"route", row.route},
                 {"length_m", row.length},
                 {"feasible", row.feasible},
                 {"viewpoints",
                  row.feasible ? json(row.viewpoints.size()) : json(nullptr)},
                 {"fail_at_m", row.feasible ? json(nullptr) : json(row.reach)},
                 {"fail_x", row.feasible ? json(nullptr) : json(row.failAt.x)},
                 {"fail_y", row.feasible ? json(nullptr) : json(row.failAt.y)},
                 {"min_allowed_error_m", finite(row.minAllowed)},
                 {"strategies", {{"A", cnt[0]}, {"B", cnt[1]}, {"C", cnt[2]}}},
                 {"evaluations", row.evaluations},
                 {"degenerate_observations", row.degenerate},
                 {"optimal", isOpt}});
        }
        std::string note;
        if (!sp.startFree)
            note = "start within R + S of an obstacle";
        else if (!sp.goalFree)
            note = "goal within R + S of an obstacle";
        else if (sp.rows.empty())
            note = "no path";
        sweep.push_back({{"S", sp.S},
                         {"start_free", sp.startFree},
                         {"goal_free", sp.goalFree},
                         {"graph_nodes", sp.nodes},
                         {"graph_edges", sp.edges},
                         {"note", note},
                         {"paths", paths}});
    }
    csv.close();
    return sweep;
}

// sweep.md: 004 Tables II/III (per S the chosen path), then every row.
void writeSweepMd(const CViewpointPlanner& p, const TPlanRow* opt, COutputDir& out) {
    std::ostringstream md;
    md << "# Path and viewpoint sweep\n\n"
       << "Per safety margin S the shortest feasible path (then the fewest "
          "viewpoints), "
          "as in Yamashita et al. 004 Tables II/III. Optimal: **bold**.\n\n"
       << "| S [mm] | route | path length [mm] | viewpoints "
          "|\n|---:|---:|---:|---:|\n";
    for (const auto& sp : p.sweep()) {
        const TPlanRow* b = bestOfS(sp, p.options.length_tolerance);
        const bool o = b && b == opt;
        char line[160];
        if (b)
            std::snprintf(line, sizeof(line), "| %s%.0f%s | %d | %.0f | %zu |\n",
                          o ? "**" : "", sp.S * 1000, o ? " (optimal)**" : "", b->route,
                          b->length * 1000, b->viewpoints.size());
        else
            std::snprintf(line, sizeof(line), "| %.0f | - | - | - |\n", sp.S * 1000);
        md << line;
    }
    md << "\nEvery (S, path): route = homotopy class (1 = the class of the shortest "
          "path).\n\n| S [mm] | path | route | length [mm] | feasible | viewpoints | "
          "fails at [mm] |\n|---:|---:|---:|---:|---|---:|---:|\n";
    for (const auto& sp : p.sweep())
        for (size_t r = 0; r < sp.rows.size(); r++) {
            const auto& row = sp.rows[r];
            char line[200];
            std::snprintf(
                line, sizeof(line), "| %.0f | %zu | %d | %.0f | %s | %s | %s |\n",
                sp.S * 1000, r + 1, row.route, row.length * 1000,
                row.feasible ? "yes" : "no",
                row.feasible ? std::to_string(row.viewpoints.size()).c_str() : "-",
                row.feasible
                    ? "-"
                    : std::to_string(long(std::lround(row.reach * 1000))).c_str());
            md << line;
        }
    out.writeText("sweep.md", md.str());
}

// strategies.csv: the optimal plan's viewpoints, every strategy's best
// option there (003 Table 1's layout), the chosen one flagged; the
// viewpoints for summary.json.
json writeStrategiesCsv(const CViewpointPlanner& p, const TPlanRow* opt,
                        COutputDir& out) {
    const auto& lms = p.world().landmarks;
    CCsvWriter st(out.stage("strategies.csv"),
                  {"viewpoint", "s_m", "x", "y", "heading_deg", "strategy", "chosen",
                   "landmarks", "pan_left_deg", "pan_right_deg", "e_pos_m", "d_phi_deg",
                   "m_m", "e_ang_m", "e_max_m", "reach_m"});
    json vps = json::array();
    if (opt)
        for (size_t v = 0; v < opt->viewpoints.size(); v++) {
            const auto& vp = opt->viewpoints[v];
            for (const auto& alt : vp.eval.perStrategy) {
                if (!alt)
                    continue;
                const bool chosen =
                    vp.eval.best && alt->obs.strategy == vp.eval.best->obs.strategy;
                st.row({std::to_string(v + 1), num(vp.at.s), num(vp.at.x), num(vp.at.y),
                        num(deg(vp.at.heading)),
                        std::string(1, letter(alt->obs.strategy)),
                        chosen ? "true" : "false", landmarkList(alt->obs, lms),
                        num(deg(alt->obs.pan[0])), num(deg(alt->obs.pan[1])),
                        num(alt->err.ePos), num(deg(alt->err.dPhi)), num(vp.m),
                        num(angularError(vp.m, alt->err.dPhi)),
                        num(totalError(alt->err, vp.m)), num(alt->reach)});
            }
            const auto& b = *vp.eval.best;
            json alts = json::object();
            for (const auto& alt : vp.eval.perStrategy)
                if (alt)
                    alts[std::string(1, letter(alt->obs.strategy))] = {
                        {"landmarks", landmarkList(alt->obs, lms)},
                        {"e_pos_m", alt->err.ePos},
                        {"d_phi_deg", deg(alt->err.dPhi)},
                        {"e_max_m", totalError(alt->err, vp.m)}};
            vps.push_back({{"s_m", vp.at.s},
                           {"x", vp.at.x},
                           {"y", vp.at.y},
                           {"heading_deg", deg(vp.at.heading)},
                           {"strategy", std::string(1, letter(b.obs.strategy))},
                           {"landmarks", landmarkList(b.obs, lms)},
                           {"pan_left_deg", deg(b.obs.pan[0])},
                           {"pan_right_deg", deg(b.obs.pan[1])},
                           {"e_pos_m", b.err.ePos},
                           {"d_phi_deg", deg(b.err.dPhi)},
                           {"m_m", vp.m},
                           {"e_max_m", totalError(b.err, vp.m)},
                           {"allowed_error_m", vp.at.allowed},
                           {"alternatives", alts}});
        }
    st.close();
    return vps;
}

// waypoints.ini: MRPT's TWaypointSequence (section [Waypoints]); its points
// for summary.json.
json writeWaypointsIni(const CViewpointPlanner& p, const TPlanRow* opt, COutputDir& out) {
    const auto& lms = p.world().landmarks;
    json wpts = json::array();
    if (opt) {
        const TPlanWaypoints pw = planWaypoints(*opt);
        mrpt::config::CConfigFileMemory ini;
        // The keys of MRPT's TWaypointSequence::save(), written here with
        // every digit (MRPT's own save keeps 6 significant digits past 1e4 m).
        ini.write("Waypoints", "waypoint_count", std::to_string(pw.points.size()));
        for (size_t i = 0; i < pw.points.size(); i++) {
            const bool vp = pw.viewpoint[i] >= 0;
            auto put = [&](const char* field, const std::string& v) {
                char key[48];
                std::snprintf(key, sizeof(key), "wp%03zu_%s", i, field);
                ini.write("Waypoints", key, v);
            };
            put("allowed_distance", numberText(std::max(0.05, p.options.sample_step)));
            put("allow_skip", vp ? "false" : "true");
            put("target_x", numberText(pw.points[i].x));
            put("target_y", numberText(pw.points[i].y));
            put("target_frame_id", "map");
            put("speed_ratio", "1");
            wpts.push_back({pw.points[i].x, pw.points[i].y});
            if (vp) {
                const auto& b = *opt->viewpoints[size_t(pw.viewpoint[i])].eval.best;
                ini.write("Viewpoints", "waypoint_" + std::to_string(i),
                          std::string(1, letter(b.obs.strategy)) + " " +
                              landmarkList(b.obs, lms) +
                              " pan_left_deg=" + numberText(deg(b.obs.pan[0])) +
                              " pan_right_deg=" + numberText(deg(b.obs.pan[1])));
            }
        }
        out.writeText(
            "waypoints.ini",
            // ';' comments: MRPT's ini parser reads a "//" line holding '='
            // as a key of the unnamed section.
            "; risknav-viewpoint-plan: the optimal plan as an MRPT "
            "TWaypointSequence (TWaypointSequence::load(cfg, \"Waypoints\"));\n"
            "; [Viewpoints] waypoint_N = strategy landmarks pans: observe there "
            "(those waypoints have allow_skip = false)\n" +
                ini.getContent());
    }
    return wpts;
}

/** The optimal plan for summary.json (null: none). */
json optimalJson(const TPlanRow* opt, const json& wpts, const json& vps) {
    if (opt) {
        size_t cnt[3] = {0, 0, 0};
        for (const auto& vp : opt->viewpoints)
            cnt[size_t(vp.eval.best->obs.strategy) - size_t('A')]++;
        json path = json::array();
        for (const auto& q : opt->path)
            path.push_back({q.x, q.y});
        return {{"S", opt->S},
                {"path", opt->rank + 1},
                {"route", opt->route},
                {"length_m", opt->length},
                {"viewpoints", opt->viewpoints.size()},
                {"strategies", {{"A", cnt[0]}, {"B", cnt[1]}, {"C", cnt[2]}}},
                {"path_vertices", path},
                {"waypoints", wpts},
                {"viewpoint_list", vps}};
    }
    return nullptr;
}

// Monte Carlo of the image errors on every feasible plan.
json monteCarloJson(const CViewpointPlanner& p) {
    CViewpointPlanner::TMonteCarlo all;
    size_t plans = 0;
    for (const auto& sp : p.sweep())
        for (const auto& row : sp.rows) {
            if (!row.feasible)
                continue;
            plans++;
            const auto mc = p.monteCarlo(row, size_t(p.options.monte_carlo_draws),
                                         p.options.seed + plans);
            all.draws += mc.draws;
            all.failures += mc.failures;
            all.maxRatioPos = std::max(all.maxRatioPos, mc.maxRatioPos);
            all.maxRatioTotal = std::max(all.maxRatioTotal, mc.maxRatioTotal);
        }
    return {{"plans", plans},
            {"draws", all.draws},
            {"failures", all.failures},
            {"max_ratio_position", all.maxRatioPos},
            {"max_ratio_total", all.maxRatioTotal}};
}

/** The world and the parameters planned with, for summary.json. */
void addWorldJson(const CViewpointPlanner& p, json& j) {
    const auto& w = p.world();
    json lmList = json::array();
    for (const auto& l : w.landmarks)
        lmList.push_back({{"id", l.id},
                          {"x", l.x},
                          {"y", l.y},
                          {"facing_deg", deg(l.facing)},
                          {"radius", l.radius}});
    j["world"] = {
        {"file", p.options.world_file},
        {"bounds", {w.xMin, w.yMin, w.xMax, w.yMax}},
        {"obstacles", w.obstacles.size()},
        {"landmarks", w.landmarks.size()},
        {"landmark_list", lmList}};  // as planned with (moved onto a traced wall)
    const TCameraRig rig = p.camera.rig();
    j["parameters"] = {{"robot_radius", p.robot.radius},
                       {"camera_offset", rig.b_r},
                       {"focal_px", rig.focal},
                       {"image", {rig.width, rig.height}},
                       {"du_px", p.camera.du_px},
                       {"dv_px", p.camera.dv_px},
                       {"dr_px", p.camera.dr_px},
                       {"dead_reckoning", p.options.dead_reckoning},
                       {"k_paths", p.options.k_paths},
                       {"sample_step", p.options.sample_step},
                       {"safety_margins", p.options.safety_margins}};
}
}  // namespace

TPlanWaypoints planWaypoints(const TPlanRow& row) {
    TPlanWaypoints w;
    size_t v = 0;
    double s = 0;
    for (size_t i = 0; i < row.path.size(); i++) {
        if (i > 0) {
            const double L = std::hypot(row.path[i].x - row.path[i - 1].x,
                                        row.path[i].y - row.path[i - 1].y);
            // Viewpoints strictly inside this segment, in order.
            while (v < row.viewpoints.size() && row.viewpoints[v].at.s < s + L - 1e-9) {
                if (row.viewpoints[v].at.s > s + 1e-9) {
                    w.points.push_back({row.viewpoints[v].at.x, row.viewpoints[v].at.y});
                    w.viewpoint.push_back(int(v));
                } else if (!w.viewpoint.empty()) {
                    w.viewpoint.back() = int(v);  // on the vertex just added
                }
                v++;
            }
            s += L;
        }
        w.points.push_back(row.path[i]);
        w.viewpoint.push_back(-1);
    }
    // A viewpoint exactly at the goal marks the last vertex.
    if (v < row.viewpoints.size())
        w.viewpoint.back() = int(v);
    return w;
}

json writeViewpointReport(const CViewpointPlanner& p, COutputDir& out) {
    const TPlanRow* opt = optimalRow(p);
    json j;
    j["status"] = opt ? "ok" : "no feasible plan";
    j["sweep"] = writeSweepCsv(p, opt, out);
    j["routes"] = p.routeCount();
    writeSweepMd(p, opt, out);
    const json vps = writeStrategiesCsv(p, opt, out);
    const json wpts = writeWaypointsIni(p, opt, out);
    j["optimal"] = optimalJson(opt, wpts, vps);
    j["monte_carlo"] = monteCarloJson(p);
    drawPlan(p, out.stage("plan.png"));
    addWorldJson(p, j);
    return j;
}

void runViewpointPlanApp(const TAppContext& ctx) {
    const auto t0 = std::chrono::steady_clock::now();
    CViewpointPlanner planner;
    planner.loadFromConfigFile(ctx.cfg);
    if (ctx.args.seed)
        planner.options.seed = *ctx.args.seed;
    COutputDir out(ctx.args.outDir, ctx.info.name);
    planner.plan();
    const double planSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    json summary = summaryHeader(ctx, planner.options.seed);
    summary.update(writeViewpointReport(planner, out));
    summary["timing"] = {
        {"plan_s", planSeconds},
        {"wall_time_s",
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}};
    mrpt::config::CConfigFileMemory effective;
    planner.saveToConfigFile(effective);
    commitRun(ctx, out, summary, effective);
    if (!ctx.args.quiet) {
        if (const auto o = planner.optimal()) {
            const auto& r = planner.sweep()[o->first].rows[o->second];
            std::fprintf(
                stderr,
                "%s: optimal S = %.3f m, route %d, %.3f m, %zu viewpoints -> %s\n",
                ctx.info.name.c_str(), r.S, r.route, r.length, r.viewpoints.size(),
                out.dir().c_str());
        } else
            std::fprintf(stderr, "%s: no feasible plan -> %s\n", ctx.info.name.c_str(),
                         out.dir().c_str());
    }
}

}  // namespace risknav::viewpoint
