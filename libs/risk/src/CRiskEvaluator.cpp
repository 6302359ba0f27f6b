#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/planning/CGlobalPlanner.h>
#include <risknav/risk/CRiskEvaluator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
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

std::string fmtPoint(const TPoint2D& p) {
    return pointText(p.x, p.y);
}

// The longest cov_ file a run may write: the longest route name with the
// longest names of as many sensing points as a row may visit, and the sensing
// point to name in a message (nullptr: no sensing points).
std::pair<const TSensingPointOptions*, std::string> longestCovFile(
    const CRiskEvaluator& ev) {
    if (ev.sensingPoints.empty() || ev.options.max_sensing_subset <= 0)
        return {nullptr, ""};
    std::vector<const TSensingPointOptions*> longest;
    for (const auto& p : ev.sensingPoints)
        longest.push_back(&p);
    std::stable_sort(longest.begin(), longest.end(), [](const auto* a, const auto* b) {
        return a->name.size() > b->name.size();
    });
    longest.resize(std::min(longest.size(), size_t(ev.options.max_sensing_subset)));
    std::vector<std::string> visit;
    for (const auto* p : longest)
        visit.push_back(p->name);
    std::string route;
    if (ev.options.gvg_routes > 0)
        route = CRiskEvaluator::gvgRouteName(size_t(ev.options.gvg_routes));
    if (ev.options.grid_routes > 0) {
        const auto g = CRiskEvaluator::gridRouteName(size_t(ev.options.grid_routes));
        if (g.size() > route.size())
            route = g;
    }
    for (const auto& r : ev.configRoutes)
        if (r.name.size() > route.size())
            route = r.name;
    return {longest.front(), CRiskEvaluator::covFileName(route, visit)};
}
}  // namespace

void CRiskEvaluator::TOptions::declare(Visitor& v) {
    v.include(map);
    v.include(obstacles);
    v.point(start, "start", TRange::any("m"),
            "x y; on the map and not in a (grown) obstacle");
    v.point(goal, "goal", TRange::any("m"), "x y; the same, and not the start");
    v.number(u_threshold, "u_threshold",
             TRange::nonNegative("(u = 1/D_max^2 is dimensionless)"),
             "exclude a route whose max u exceeds this (section 5.3); 0 = off");
    v.integer(max_sensing_subset, "max_sensing_subset", TRange::closed(0, 6),
              "evaluate every subset of sensing points up to this size");
    v.integer(gvg_routes, "gvg_routes", TRange::closed(0, 50),
              "the k shortest distinct GVG routes (0 = none)");
    v.integer(grid_routes, "grid_routes", TRange::closed(0, 10),
              "the k least-cost grid ways of distinct homotopy classes (0 = none)");
    v.include(gvg);
    v.number(ellipse_interval, "ellipse_interval", TRange::closed(0.1, 100, "m"),
             "between the ellipses drawn in ellipses_*.png");
    v.number(eval_step, "eval_step", TRange::closed(0.005, 5, "m"),
             "D_max / u sampling along the path");
    v.seed(seed, "seed", "of [Odometry] propagation = sampled; --seed overrides");
}

void CRiskEvaluator::TOptions::validateRules() const {
    checkRule(std::hypot(goal.x - start.x, goal.y - start.y) > 1e-6, section, "goal",
              fmtPoint(goal), "the goal must differ from the start");
}

void CRiskEvaluator::loadFromConfigFile(const CIniConfig& c) {
    m_where = configWhere(c);
    for (const auto& s : c.sections())
        if (s != "RiskEval" && s != "Robot" && s != "Odometry" && !numbered(s, "Route") &&
            !numbered(s, "SensingPoint"))
            c.throwUnknownSection(s, "RiskEval, Robot, Odometry, RouteN, SensingPointN");
    if (!c.sectionExists("RiskEval"))
        throw CBadInputError(c.path() + ": missing section [RiskEval]");
    options.loadFromConfigFile(c, "RiskEval");
    robot.loadFromConfigFile(c, "Robot");
    odometry.loadFromConfigFile(c, "Odometry");
    propagation.loadFromConfigFile(c, "Odometry");
    std::vector<std::string> secs = c.sections();
    std::sort(secs.begin(), secs.end());
    configRoutes.clear();
    sensingPoints.clear();
    for (const auto& s : secs)
        if (numbered(s, "SensingPoint")) {
            sensingPoints.emplace_back();
            sensingPoints.back().loadFromConfigFile(c, s);
        } else if (numbered(s, "Route")) {
            configRoutes.emplace_back();
            configRoutes.back().loadFromConfigFile(c, s);
        }
    c.throwOnUnreadKeys();
    try {
        prepare();
    } catch (const CConfigKeyError& e) {
        throw CBadInputError(configWhere(c, e.section, e.key) + typedValueMessage(c, e));
    }
}

void CRiskEvaluator::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    options.saveToConfigFile(c, "RiskEval");
    robot.saveToConfigFile(c, "Robot");
    odometry.saveToConfigFile(c, "Odometry");
    propagation.saveToConfigFile(c, "Odometry");
    for (const auto& r : configRoutes)
        r.saveToConfigFile(c, r.section);
    for (const auto& p : sensingPoints)
        p.saveToConfigFile(c, p.section);
}

void CRiskEvaluator::validate() const {
    options.validate();
    robot.validate();
    odometry.validate();
    propagation.validate();
    std::set<std::string> routeNames;
    // Names become file names (cov_<name>.csv, ellipses_<name>.png): two that
    // give one file name would overwrite each other's files. Refused rather
    // than numbered, so that the files keep the names the config gives.
    std::map<std::string, std::string> routeFiles;  // file part -> "[RouteN] name = 'x'"
    for (size_t k = 1; k <= size_t(std::max(0, options.gvg_routes)); k++)
        routeFiles[fileNamePart(gvgRouteName(k))] =
            "GVG route " + gvgRouteName(k) + " ([" + options.section +
            "] gvg_routes = " + std::to_string(options.gvg_routes) + ")";
    for (size_t k = 1; k <= size_t(std::max(0, options.grid_routes)); k++)
        routeFiles[fileNamePart(gridRouteName(k))] =
            "grid way " + gridRouteName(k) + " ([" + options.section +
            "] grid_routes = " + std::to_string(options.grid_routes) + ")";
    routeFiles["best"] = "the best row (ellipses_best.png)";
    for (const auto& r : configRoutes) {
        r.validate();
        // (risknav-navigate's risk_route picks a route by its name)
        checkRule(routeNames.insert(r.name).second, r.section, "name", r.name,
                  "another route has this name");
        const std::string part = fileNamePart(r.name);
        const auto [it, fresh] =
            routeFiles.emplace(part, "[" + r.section + "] name = '" + r.name + "'");
        checkRule(fresh, r.section, "name", r.name,
                  "its files " + covFileName(r.name, {}) + " and " +
                      ellipsesFileName(r.name) + " would be those of " + it->second +
                      " (file names keep letters, digits, '-' and '_'); rename one");
        checkOutputFileName(r.section, "name", r.name, covFileName(r.name, {}));
        checkOutputFileName(r.section, "name", r.name, ellipsesFileName(r.name));
    }
    std::set<std::string> names;
    std::map<std::string, std::string> pointFiles;
    for (const auto& p : sensingPoints) {
        p.validate();
        checkRule(names.insert(p.name).second, p.section, "name", p.name,
                  "another sensing point has this name");
        const auto [it, fresh] = pointFiles.emplace(
            fileNamePart(p.name), "[" + p.section + "] name = '" + p.name + "'");
        checkRule(fresh, p.section, "name", p.name,
                  "in file names (cov_<route>+" + fileNamePart(p.name) +
                      ".csv) it would be " + it->second +
                      " (file names keep letters, digits, '-' and '_'); rename one");
    }
    if (const auto [p, file] = longestCovFile(*this); p)
        checkOutputFileName(p->section, "name", p->name, file);
    checkRule(!configRoutes.empty() || options.gvg_routes > 0 || options.grid_routes > 0,
              options.section, "gvg_routes", std::to_string(options.gvg_routes),
              "no candidate routes: add [RouteN] sections or set [RiskEval] gvg_routes "
              "or grid_routes > 0");
    // The work of a run, as far as the config decides it.
    const size_t routes =
        configRoutes.size() + size_t(options.gvg_routes) + size_t(options.grid_routes);
    checkRule(routes <= kMaxRoutes, options.section, "gvg_routes",
              std::to_string(options.gvg_routes),
              std::to_string(configRoutes.size()) + " [RouteN] sections + gvg_routes " +
                  std::to_string(options.gvg_routes) + " + grid_routes " +
                  std::to_string(options.grid_routes) + " = " + std::to_string(routes) +
                  " candidate routes; at most " + std::to_string(kMaxRoutes));
    const double rows = double(routes) * sensingSubsets();
    char b[200];
    std::snprintf(b, sizeof(b),
                  "%zu candidate routes x %.0f subsets of the %zu sensing points = %.0f "
                  "rows to evaluate; at most %zu (fewer sensing points or a smaller "
                  "max_sensing_subset)",
                  routes, sensingSubsets(), sensingPoints.size(), rows, kMaxRows);
    checkRule(rows <= double(kMaxRows), options.section, "max_sensing_subset",
              std::to_string(options.max_sensing_subset), b);
}

double CRiskEvaluator::sensingSubsets() const {
    // sum_{k = 0}^{min(n, max)} C(n, k), in doubles (no overflow).
    const int n = int(sensingPoints.size());
    double sum = 0, c = 1;
    for (int k = 0; k <= std::min(n, options.max_sensing_subset); k++) {
        sum += c;
        c = c * double(n - k) / double(k + 1);
    }
    return sum;
}

size_t CRiskEvaluator::trajectoriesPerStep() const {
    const TRiskOptions o = riskOptions();
    const size_t n = o.model == TErrorModel::Systematic ? 6 : 3;
    switch (o.propagation) {
        case TPropagation::Linear:
            return 1;
        case TPropagation::Unscented:
            return 2 * n;
        case TPropagation::Cubature5:
            return 2 * n * n + 1;
        default:
            return size_t(o.samples);
    }
}

void CRiskEvaluator::prepare() {
    m_field.reset();  // kept only when every check below passes
    validate();
    m_gvg.reset();
    m_routes.clear();
    m_rows.clear();
    m_best = -1;
    m_grid = loadOccupancyGrid(options.map);
    auto field =
        std::make_unique<CObstacleField>(m_grid, options.obstacles, robot.radius);
    auto onMap = [&](const TPoint2D& p) {
        return p.x >= m_grid.getXMin() && p.x <= m_grid.getXMax() &&
               p.y >= m_grid.getYMin() && p.y <= m_grid.getYMax();
    };
    const std::string grown =
        "grown by robot_radius: [Robot] radius = " + numberText(robot.radius) + " m";
    const std::string& R = options.section;
    for (const auto& [key, p] :
         {std::make_pair("start", options.start), std::make_pair("goal", options.goal)}) {
        checkRule(onMap(p), R, key, fmtPoint(p), "outside the map");
        checkRule(!field->isObstacleAt(p.x, p.y), R, key, fmtPoint(p),
                  "inside an obstacle (" + grown + ")");
    }
    for (const auto& sp : sensingPoints) {
        const TPoint2D p(sp.x, sp.y);
        checkRule(onMap(p), sp.section, "x", fmtPoint(p),
                  "sensing point outside the map");
        checkRule(!field->isObstacleAt(p.x, p.y), sp.section, "x", fmtPoint(p),
                  "sensing point inside an obstacle (" + grown + ")");
    }
    for (const auto& r : configRoutes)
        for (size_t i = 0; i + 1 < r.waypoints.size(); i += 2) {
            const TPoint2D p(r.waypoints[i], r.waypoints[i + 1]);
            checkRule(
                onMap(p), r.section, "waypoints", fmtPoint(p),
                "route " + r.name + ": point " + fmtPoint(p) + " is outside the map");
        }
    m_field = std::move(field);
}

TRiskOptions CRiskEvaluator::riskOptions() const {
    return makeRiskOptions(odometry, propagation, options.eval_step, options.seed);
}

namespace {
/** Every subset of n sensing points (by index) of at most maxSize points,
 * the empty one first, then by size, each size in colexicographic order. */
std::vector<std::vector<size_t>> sensingPointSubsets(size_t n, size_t maxSize) {
    std::vector<std::vector<size_t>> subsets = {{}};
    for (size_t k = 1; k <= std::min(n, maxSize); k++) {
        std::vector<size_t> c(k);
        std::iota(c.begin(), c.end(), 0);
        for (;;) {
            subsets.push_back(c);
            size_t i = 0;
            while (i < k && c[i] + 1 == (i + 1 < k ? c[i + 1] : n))
                i++;
            if (i == k)
                break;
            c[i]++;
            std::iota(c.begin(), c.begin() + long(i), 0);
        }
    }
    return subsets;
}
}  // namespace

void CRiskEvaluator::evaluate() {
    if (!m_field)
        prepare();
    const TRiskOptions risk = riskOptions();
    const TPoint2D &start = options.start, &goal = options.goal;
    // The configured routes run from start to goal: add them unless already there.
    m_routes.clear();
    for (const auto& r : configRoutes) {
        TRoute route{r.name, {}, "config"};
        for (size_t i = 0; i + 1 < r.waypoints.size(); i += 2)
            route.waypoints.emplace_back(r.waypoints[i], r.waypoints[i + 1]);
        auto& w = route.waypoints;
        if (w.empty() || std::hypot(w.front().x - start.x, w.front().y - start.y) > 1e-6)
            w.insert(w.begin(), start);
        if (std::hypot(w.back().x - goal.x, w.back().y - goal.y) > 1e-6)
            w.push_back(goal);
        m_routes.push_back(route);
    }
    m_gvg.reset();
    if (options.gvg_routes > 0) {
        m_gvg = std::make_unique<CGvgRoutes>(*m_field, options.gvg);
        const auto g = m_gvg->routes(start, goal, size_t(options.gvg_routes));
        for (size_t i = 0; i < g.size(); i++)
            m_routes.push_back({gvgRouteName(i + 1), g[i], "gvg"});
    }
    const size_t firstGrid = m_routes.size();
    m_noWayFailure.clear();
    m_noWayReason.clear();
    if (options.grid_routes > 0) {
        // the same disc and obstacle rule as the field the routes are
        // scored on: a way the planner finds is one the field lets through
        planning::CGlobalPlanner planner;
        planner.setMap(m_grid, options.obstacles, robot.radius);
        const auto ways = planner.alternatives(start, goal, options.grid_routes);
        for (const auto& w : ways)
            if (w.found)
                m_routes.push_back({gridRouteName(m_routes.size() + 1 - firstGrid),
                                    planner.legs(w), "grid"});
        if (!ways.empty() && !ways.front().found) {
            m_noWayFailure = ways.front().failure;
            m_noWayReason = ways.front().reason;
        }
    }
    // (validate() bounded the number of subsets)
    const std::vector<std::vector<size_t>> subsets =
        sensingPointSubsets(sensingPoints.size(), size_t(options.max_sensing_subset));
    m_rows.clear();
    m_best = -1;
    for (size_t r = 0; r < m_routes.size(); r++)
        for (const auto& sub : subsets) {
            TRow row;
            row.route = r;
            row.sensing = sub;
            std::vector<TSensingPoint> visit;
            for (size_t i : sub)
                visit.push_back(sensingPoints[i].point());
            row.feasible =
                routeWithSensingDetours(m_routes[r].waypoints, visit, *m_field, row.path);
            if (!row.feasible) {
                row.excluded = true;
                row.reason =
                    "a sensing point cannot be reached in a straight line from the route";
            }
            m_rows.push_back(row);
        }
    // The work, before any of it is done.
    TStepCount steps;
    for (const auto& row : m_rows)
        if (row.feasible) {
            const TStepCount n =
                motionStepCount(row.path, risk.speed, risk.turnRate, risk.tau);
            steps.straight += n.straight;
            steps.turning += n.turning;
        }
    m_steps = steps.total();
    m_trajSteps = m_steps * double(trajectoriesPerStep());
    auto tooMuch = [&](const std::string& key, const std::string& value,
                       const std::string& rule) {
        throw CBadInputError(m_where + "[" + propagation.section + "] " + key + " = '" +
                             value + "': " + rule);
    };
    char b[400];
    if (m_steps > kMaxSteps) {
        const bool turns = steps.turning > steps.straight;
        std::snprintf(b, sizeof(b),
                      "the %zu rows need %.3g propagation steps (%s / (%s x tau), tau = "
                      "%s s); at most %.3g: raise %s or tau, or evaluate fewer rows",
                      m_rows.size(), m_steps, turns ? "turn angles" : "path lengths",
                      turns ? "turn_rate_deg" : "speed",
                      numberText(propagation.tau).c_str(), kMaxSteps,
                      turns ? "turn_rate_deg" : "speed");
        tooMuch(turns ? "turn_rate_deg" : "speed",
                numberText(turns ? propagation.turn_rate_deg : propagation.speed), b);
    }
    if (m_trajSteps > kMaxTrajectorySteps) {
        std::snprintf(b, sizeof(b),
                      "the %zu rows need %.3g propagation steps x %zu trajectories = "
                      "%.3g trajectory steps; at most %.3g: a cheaper propagation (fewer "
                      "samples, cubature5, linear), a larger tau or fewer rows",
                      m_rows.size(), m_steps, trajectoriesPerStep(), m_trajSteps,
                      kMaxTrajectorySteps);
        tooMuch("propagation", propagation.propagation, b);
    }
    // Evaluate. Only the plain row and the best row of each route keep their
    // samples (cov_*.csv, images); the table has every row.
    std::vector<long> routeBest(m_routes.size(), -1);
    for (size_t k = 0; k < m_rows.size(); k++) {
        TRow& row = m_rows[k];
        if (!row.feasible)
            continue;
        std::vector<TSensingPoint> visit;
        for (size_t i : row.sensing)
            visit.push_back(sensingPoints[i].point());
        row.result = evaluatePathRisk(row.path, visit, *m_field, risk);
        if (!row.result.failure.empty()) {
            row.excluded = true;
            row.reason = row.result.failure;
        } else if (row.result.blocked) {
            row.excluded = true;
            row.reason = "collides with an obstacle";
        } else if (options.u_threshold > 0 && row.result.uMax > options.u_threshold) {
            row.excluded = true;
            row.reason = "max u above u_threshold";
        }
        auto beats = [&](long other) {
            return other < 0 || row.result.U < m_rows[size_t(other)].result.U;
        };
        long& rb = routeBest[row.route];
        const bool best = !row.excluded && beats(rb);
        if (best) {
            if (rb >= 0 && !m_rows[size_t(rb)].sensing.empty())
                m_rows[size_t(rb)].result.samples = {};
            rb = long(k);
        } else if (!row.sensing.empty())
            row.result.samples = {};
        if (!row.excluded && beats(m_best))
            m_best = long(k);
    }
}

std::string CRiskEvaluator::fileNamePart(const std::string& name) {
    std::string s = name;
    for (char& ch : s)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_')
            ch = '_';
    return s;
}

std::string CRiskEvaluator::covFileName(const std::string& route,
                                        const std::vector<std::string>& sensing) {
    std::string s = "cov_" + fileNamePart(route);
    for (const auto& p : sensing)
        s += "+" + fileNamePart(p);
    return s + ".csv";
}

std::string CRiskEvaluator::ellipsesFileName(const std::string& route) {
    return "ellipses_" + fileNamePart(route) + ".png";
}

std::string CRiskEvaluator::gvgRouteName(size_t k) {
    return "G" + std::to_string(k);
}

std::string CRiskEvaluator::gridRouteName(size_t k) {
    return "W" + std::to_string(k);
}

void CRiskEvaluator::checkOutputPaths(const mrpt::config::CConfigFileBase& c,
                                      const std::string& outDir) const {
    for (const auto& r : configRoutes) {
        checkOutputPath(c, r.section, "name", r.name, outDir, covFileName(r.name, {}));
        checkOutputPath(c, r.section, "name", r.name, outDir, ellipsesFileName(r.name));
    }
    if (const auto [p, file] = longestCovFile(*this); p)
        checkOutputPath(c, p->section, "name", p->name, outDir, file);
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
