#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/risk/CRiskEvaluator.h>

#include <algorithm>
#include <cstdio>
#include <set>

using namespace risknav::common;
using mrpt::math::TPoint2D;

namespace risknav::risk {
namespace {
bool numbered(const std::string& s, const std::string& prefix) {
    return s.size() > prefix.size() && s.compare(0, prefix.size(), prefix) == 0 &&
           std::all_of(s.begin() + prefix.size(), s.end(),
                       [](unsigned char ch) { return std::isdigit(ch); });
}

TPoint2D readPoint(const mrpt::config::CConfigFileBase& c, const std::string& s,
                   const std::string& k) {
    const auto v = readNumbers(c, s, k, {}, TRange::any("m"));
    if (v.size() != 2)
        throw CBadInputError(configWhere(c) + "[" + s + "] " + k +
                             ": required, as x y [m]");
    return {v[0], v[1]};
}

std::string fmtPoint(const TPoint2D& p) {
    char b[64];
    std::snprintf(b, sizeof(b), "(%.2f, %.2f)", p.x, p.y);
    return b;
}
}  // namespace

void CRiskEvaluator::loadFromConfigFile(const CIniConfig& c) {
    for (const auto& s : c.sections())
        if (s != "RiskEval" && s != "Odometry" && !numbered(s, "Route") &&
            !numbered(s, "SensingPoint"))
            throw CBadInputError(c.path() + ": unknown section [" + s +
                                 "] (known: RiskEval, Odometry, RouteN, SensingPointN)");
    if (!c.sectionExists("RiskEval"))
        throw CBadInputError(c.path() + ": missing section [RiskEval]");
    const std::string R = "RiskEval", O = "Odometry";
    loadOptions(mapSource, c, R);
    fieldOptions.occupied_threshold =
        readDouble(c, R, "occupied_threshold", 0.65, TRange::closed(0.01, 1));
    fieldOptions.free_threshold =
        readDouble(c, R, "free_threshold", 0.35, TRange::closed(0, 0.99));
    if (fieldOptions.free_threshold >= fieldOptions.occupied_threshold)
        throwBadKey(c, R, "free_threshold", std::to_string(fieldOptions.free_threshold),
                    "must be < occupied_threshold");
    fieldOptions.unknown_is_obstacle = readBool(c, R, "unknown_is_obstacle", true);
    fieldOptions.robot_radius =
        readDouble(c, R, "robot_radius", 0.25, TRange::closed(0, 5, "m"));
    start = readPoint(c, R, "start");
    goal = readPoint(c, R, "goal");
    uThreshold = readDouble(c, R, "u_threshold", 0.0,
                            TRange::nonNegative("(u = 1/D_max^2 is dimensionless)"));
    maxSensingSubset = readInt(c, R, "max_sensing_subset", 2, TRange::closed(0, 6));
    gvgRoutes = readInt(c, R, "gvg_routes", 3, TRange::closed(0, 50));
    gvgOptions.separation_ratio =
        readDouble(c, R, "gvg_separation_ratio", 1.0, TRange::closed(0.1, 2));
    gvgOptions.simplify_tolerance =
        readDouble(c, R, "gvg_simplify_tolerance", 0.1, TRange::closed(0, 2, "m"));
    ellipseInterval =
        readDouble(c, R, "ellipse_interval", 2.0, TRange::closed(0.1, 100, "m"));
    riskOptions.evalStep =
        readDouble(c, R, "eval_step", 0.05, TRange::closed(0.005, 5, "m"));

    auto& m = riskOptions.odometry;
    m.radiusL = readDouble(c, O, "wheel_radius_l", 0.063, TRange::closed(0.005, 2, "m"));
    m.radiusR = readDouble(c, O, "wheel_radius_r", 0.063, TRange::closed(0.005, 2, "m"));
    m.tread = readDouble(c, O, "tread", 0.399, TRange::closed(0.02, 5, "m"));
    m.sigmaRL = readDouble(c, O, "sigma_wheel_radius_l", 0.001, TRange::nonNegative("m"));
    m.sigmaRR = readDouble(c, O, "sigma_wheel_radius_r", 0.001, TRange::nonNegative("m"));
    m.sigmaT = readDouble(c, O, "sigma_tread", 0.001, TRange::nonNegative("m"));
    const double nx = readDouble(c, O, "noise_sigma_x", 0, TRange::nonNegative("m/s"));
    const double ny = readDouble(c, O, "noise_sigma_y", 0, TRange::nonNegative("m/s"));
    const double nt =
        readDegrees(c, O, "noise_sigma_theta_deg", 0, TRange::nonNegative("deg/s"));
    m.sigmaN = Eigen::Vector3d(nx * nx, ny * ny, nt * nt).asDiagonal();
    riskOptions.model = readChoice(c, O, "error_model", "systematic",
                                   {"systematic", "per_step"}) == "per_step"
                            ? TErrorModel::PerStep
                            : TErrorModel::Systematic;
    riskOptions.tau = readDouble(c, O, "tau", 0.05, TRange::closed(0.001, 1, "s"));
    riskOptions.speed = readDouble(c, O, "speed", 0.3, {0, 5, true, false, "m/s"});
    riskOptions.turnRate = readDegrees(c, O, "turn_rate_deg", 30 * M_PI / 180,
                                       {0, 720, true, false, "deg/s"});
    const double sx = readDouble(c, O, "init_sigma_x", 0.001, TRange::nonNegative("m"));
    const double sy = readDouble(c, O, "init_sigma_y", 0.001, TRange::nonNegative("m"));
    const double st =
        readDegrees(c, O, "init_sigma_theta_deg", 0.1, TRange::closed(0, 180, "deg"));
    riskOptions.sigmaP0 = Eigen::Vector3d(sx * sx, sy * sy, st * st).asDiagonal();

    std::vector<std::string> secs = c.sections();
    std::sort(secs.begin(), secs.end());
    std::set<std::string> names;
    for (const auto& s : secs) {
        if (numbered(s, "SensingPoint")) {
            TSensingPoint p;
            p.name = readString(c, s, "name", s);
            p.x = requireDouble(c, s, "x", TRange::any("m"));
            p.y = requireDouble(c, s, "y", TRange::any("m"));
            p.radius = readDouble(c, s, "radius", 0.1, TRange::closed(0.01, 10, "m"));
            const double a = readDouble(c, s, "sigma_x", 0.001, TRange::nonNegative("m"));
            const double b = readDouble(c, s, "sigma_y", 0.001, TRange::nonNegative("m"));
            const double t =
                readDegrees(c, s, "sigma_theta_deg", 0.1, TRange::closed(0, 180, "deg"));
            p.resetCov = Eigen::Vector3d(a * a, b * b, t * t).asDiagonal();
            if (!names.insert(p.name).second)
                throwBadKey(c, s, "name", p.name, "another sensing point has this name");
            sensingPoints.push_back(p);
        } else if (numbered(s, "Route")) {
            TRoute r;
            r.name = readString(c, s, "name", s);
            const auto v = readNumbers(c, s, "waypoints", {}, TRange::any("m"), 0, 2);
            for (size_t i = 0; i + 1 < v.size(); i += 2)
                r.waypoints.emplace_back(v[i], v[i + 1]);
            // The route runs from start to goal: add them unless already there.
            if (r.waypoints.empty() || std::hypot(r.waypoints.front().x - start.x,
                                                  r.waypoints.front().y - start.y) > 1e-6)
                r.waypoints.insert(r.waypoints.begin(), start);
            if (std::hypot(r.waypoints.back().x - goal.x, r.waypoints.back().y - goal.y) >
                1e-6)
                r.waypoints.push_back(goal);
            configRoutes.push_back(r);
        }
    }
    if (configRoutes.empty() && gvgRoutes == 0)
        throw CBadInputError(c.path() +
                             ": no candidate routes: add [RouteN] sections or set "
                             "[RiskEval] gvg_routes > 0");
    c.throwOnUnreadKeys();

    // Against the map.
    m_grid = loadOccupancyGrid(mapSource);
    m_field = std::make_unique<CObstacleField>(m_grid, fieldOptions);
    auto onMap = [&](const TPoint2D& p) {
        return p.x >= m_grid.getXMin() && p.x <= m_grid.getXMax() &&
               p.y >= m_grid.getYMin() && p.y <= m_grid.getYMax();
    };
    for (const auto& [key, p] : {std::make_pair(std::string("start"), start),
                                 std::make_pair(std::string("goal"), goal)}) {
        if (!onMap(p))
            throwBadKey(c, R, key, fmtPoint(p), "outside the map");
        if (m_field->isObstacleAt(p.x, p.y))
            throwBadKey(c, R, key, fmtPoint(p),
                        "inside an obstacle (grown by robot_radius " +
                            std::to_string(fieldOptions.robot_radius) + " m)");
    }
    for (size_t i = 0; i < sensingPoints.size(); i++) {
        const auto& p = sensingPoints[i];
        std::string sec;
        for (const auto& s : secs)
            if (numbered(s, "SensingPoint") && readString(c, s, "name", s) == p.name)
                sec = s;
        if (!onMap({p.x, p.y}))
            throwBadKey(c, sec, "x", fmtPoint({p.x, p.y}),
                        "sensing point outside the map");
        if (m_field->isObstacleAt(p.x, p.y))
            throwBadKey(c, sec, "x", fmtPoint({p.x, p.y}),
                        "sensing point inside an obstacle (grown by robot_radius)");
    }
    for (const auto& r : configRoutes)
        for (const auto& p : r.waypoints)
            if (!onMap(p))
                throw CBadInputError(c.path() + ": route " + r.name + ": point " +
                                     fmtPoint(p) + " is outside the map");
}

void CRiskEvaluator::evaluate() {
    m_routes = configRoutes;
    if (gvgRoutes > 0) {
        m_gvg = std::make_unique<CGvgRoutes>(*m_field, gvgOptions);
        const auto g = m_gvg->routes(start, goal, size_t(gvgRoutes));
        for (size_t i = 0; i < g.size(); i++)
            m_routes.push_back({"G" + std::to_string(i + 1), g[i], true});
    }
    // Every subset of sensing points up to maxSensingSubset, smallest first.
    std::vector<std::vector<size_t>> subsets = {{}};
    const size_t n = sensingPoints.size();
    for (size_t mask = 1; mask < (size_t(1) << n); mask++) {
        std::vector<size_t> s;
        for (size_t i = 0; i < n; i++)
            if (mask & (size_t(1) << i))
                s.push_back(i);
        if (int(s.size()) <= maxSensingSubset)
            subsets.push_back(s);
    }
    std::stable_sort(subsets.begin(), subsets.end(),
                     [](const auto& a, const auto& b) { return a.size() < b.size(); });
    m_rows.clear();
    m_best = -1;
    for (size_t r = 0; r < m_routes.size(); r++)
        for (const auto& sub : subsets) {
            TRow row;
            row.route = r;
            row.sensing = sub;
            std::vector<TSensingPoint> visit;
            for (size_t i : sub)
                visit.push_back(sensingPoints[i]);
            row.feasible =
                routeWithSensingDetours(m_routes[r].waypoints, visit, *m_field, row.path);
            if (!row.feasible) {
                row.excluded = true;
                row.reason =
                    "a sensing point cannot be reached in a straight line from the route";
            } else {
                row.result = evaluatePathRisk(row.path, visit, *m_field, riskOptions);
                if (row.result.blocked) {
                    row.excluded = true;
                    row.reason = "collides with an obstacle";
                } else if (uThreshold > 0 && row.result.uMax > uThreshold) {
                    row.excluded = true;
                    row.reason = "max u above u_threshold";
                }
            }
            m_rows.push_back(row);
            const size_t k = m_rows.size() - 1;
            if (!row.excluded &&
                (m_best < 0 || row.result.U < m_rows[size_t(m_best)].result.U))
                m_best = long(k);
        }
}

std::string CRiskEvaluator::sensingName(const TRow& r) const {
    if (r.sensing.empty())
        return "none";
    std::string s;
    for (size_t i : r.sensing)
        s += (s.empty() ? "" : "+") + sensingPoints[i].name;
    return s;
}

const CRiskEvaluator::TRow& CRiskEvaluator::plainRow(size_t route) const {
    for (const auto& r : m_rows)
        if (r.route == route && r.sensing.empty())
            return r;
    throw std::logic_error("no plain row");
}

}  // namespace risknav::risk
