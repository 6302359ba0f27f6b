#include <risknav/common/CAppRunner.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CNavigationRun.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/risk/CRiskEvaluator.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/CPolygon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

using namespace risknav::common;
namespace fs = std::filesystem;

namespace risknav::nav {
namespace {
const char* kSec = "Navigate";

// MRPT's reactive engine sections (2.5.8): read by MRPT with its own rules,
// so risknav reports none of their keys as unknown.
const std::set<std::string> kEngineSections = {"CAbstractNavigator",
                                               "CWaypointsNavigator",
                                               "CAbstractPTGBasedReactive",
                                               "CReactiveNavigationSystem",
                                               "CPointCloudFilterByDistance",
                                               "CHolonomicFullEval",
                                               "CHolonomicND",
                                               "CHolonomicVFF",
                                               "CMultiObjectiveMotionOptimizerBase",
                                               "CMultiObjMotionOpt_Scalarization"};

}  // namespace

void CNavigationRun::loadFromConfigFile(CIniConfig& c, std::optional<uint64_t> seed,
                                        const std::vector<std::string>& otherSections) {
    registerAllClasses_nav();
    m_cfg = &c;
    if (!c.sectionExists(kSec))
        throw CBadInputError(c.path() + ": missing section [Navigate] (start, goals)");
    if (!c.sectionExists("World"))
        throw CBadInputError(c.path() + ": missing section [World] (map_file)");
    loadOptions(options, c, kSec);
    if (seed)
        options.seed = *seed;
    world.loadFromConfigFile(c);
    m_engine.reset();
    if (!options.engine_config.empty())
        m_engine = std::make_unique<CIniConfig>(options.engine_config);
    if (options.localization == "mcl") {
        mcl.loadFromConfigFile(c);
        loadOptions(mcl.lostOptions, c, "LostLocalization");
    }
    if (options.global_planner != "none") {
        loadOptions(plannerOptions, c, "GlobalPlanner");
        if (plannerOptions.map == "built" && options.global_planner == "risk")
            throwBadKey(c, "GlobalPlanner", "map", plannerOptions.map,
                        "global_planner = risk chooses by U on the known map: "
                        "map = built needs global_planner = grid");
    }
    loadRoute(c);
    checkAgainstMap(c);
    setUpGlobalPlanner(c);
    // Too few start particles around the start lose the robot, and a lost
    // filter runs at KLD_maxSampleSize every cycle: refused before the run,
    // as risknav-afraid-learn refuses them.
    if (options.localization == "mcl") {
        mcl.options.initPose = options.start;
        try {
            mcl.checkParticles(world.grid());
        } catch (const CConfigKeyError& e) {
            throw CBadInputError(configWhere(c, e.section, e.key) +
                                 typedValueMessage(c, e));
        }
    }
    checkOutputBounds(c);

    // The engine and the limiters, through a navigator that never runs: an
    // unknown limiter, a missing section or key, a bad .afraid file, or a
    // config MRPT refuses are all exit 2 here, before any output.
    checkWithProbeNavigator(c, otherSections);
}

void CNavigationRun::setUpGlobalPlanner(const CIniConfig& c) {
    m_planner.reset();
    m_chooser.reset();
    if (options.global_planner != "none") {
        m_planner = std::make_shared<planning::CGlobalPlanner>();
        m_planner->options = plannerOptions;
        if (plannerOptions.map == "built") {
            // the robot knows the world's extent only: every cell free
            // until its laser senses it (CGlobalPlanner::TOptions::map)
            const auto& g = world.grid();
            mrpt::maps::COccupancyGridMap2D blank(g.getXMin(), g.getXMax(), g.getYMin(),
                                                  g.getYMax(), g.getResolution());
            blank.fill(0.99f);  // MRPT: a cell holds p(free)
            m_planner->setMap(blank, world.distanceField().rule(),
                              world.robot.radius + options.shape_margin);
        } else
            m_planner->setMap(world.grid(), world.distanceField().rule(),
                              world.robot.radius + options.shape_margin);
    }
    if (options.global_planner == "risk") {
        // M2's model of the robot's odometry ([Odometry]: the wheels'
        // sigmas the world drives with, the propagation), from the start's
        // error (start_sigma with localization = odometry, else none)
        loadOptions(m_propagation, c, "Odometry");
        auto ro = risk::makeRiskOptions(world.odometry.options, m_propagation, 0.05,
                                        options.seed);
        ro.sigmaP0 = Eigen::Vector3d(options.start_sigma[0] * options.start_sigma[0],
                                     options.start_sigma[1] * options.start_sigma[1],
                                     options.start_sigma[2] * options.start_sigma[2])
                         .asDiagonal();
        m_chooser = std::make_unique<risk::CRiskRouteChooser>(
            world.grid(), world.distanceField().rule(), world.robot.radius, ro,
            *m_planner);
        m_planner->routeChooser =
            [this](const std::vector<planning::TGlobalPlan>& cands) {
                return m_chooser->choose(cands);
            };
    }
}

// The outputs, bounded before the run starts (a 1e5 s run that
// never arrived was on its way to ~28 GB of navlog, ~56 KB a cycle): at
// most 36,000 navlog cycles (2 h at 0.2 s, ~2 GB) and a rawlog of at most
// 5e8 ranges (~2 GB, as risknav-simulate); one frame a cycle
void CNavigationRun::checkOutputBounds(const CIniConfig& c) const {
    const double cycles = options.duration_max / options.nav_period;
    const double rays = world.rangesPerFrame();
    const std::string dm =
        readString(c, kSec, "duration_max", numberText(options.duration_max));
    if (options.navlog && cycles > 36000 * (1 + 1e-9))
        throwBadKey(c, kSec, "duration_max", dm,
                    "is " + numberText(std::round(cycles)) +
                        " navigation cycles with navlog = true, at most 36000 (~2 "
                        "GB of navlog; lower duration_max, raise nav_period or set "
                        "navlog = false)");
    if (options.rawlog && cycles * rays > 5e8 * (1 + 1e-9))
        throwBadKey(c, kSec, "duration_max", dm,
                    "is " + numberText(std::round(cycles)) + " rawlog frames of " +
                        numberText(std::round(rays)) +
                        " ranges, at most 5e+08 ranges in all (~2 GB of rawlog; "
                        "lower duration_max or set rawlog = false)");
}

void CNavigationRun::checkWithProbeNavigator(
    CIniConfig& c, const std::vector<std::string>& otherSections) {
    sim::CSimRobotInterface probeRobot(world);
    probeRobot.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    CRiskAwareReactiveNav probe(probeRobot);
    probe.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    probe.setEngineConfig(m_engine.get());
    const_cast<mrpt::system::CTimeLogger&>(probe.getDelaysTimeLogger()).disable();
    try {
        probe.loadConfigFile(c);
        m_navigatorConfig = mrpt::config::CConfigFileMemory();
        probe.saveConfigFile(m_navigatorConfig);
        // the PTGs' build time grows with the robot's area
        probe.changeRobotShape(robotShape());
        probe.checkPtgBuildTime(c, "[Robot] radius + [Navigate] shape_margin");
    } catch (const CBadInputError&) {
        throw;
    } catch (const std::exception& e) {
        throw CBadInputError(
            (m_engine ? m_engine->path() + " (engine_config) + " : "") + c.path() +
            ": MRPT's reactive engine refused the config: " + firstLine(e.what()));
    }
    checkLaserHeight(c, probe);
    checkLimiterInputs(c, probe);
    checkSectionsKnown(c, probe, otherSections);
}

// MRPT keeps only the obstacle points within [min, max] of these
// heights: the laser's own height outside them is a blind robot
void CNavigationRun::checkLaserHeight(const CIniConfig& c,
                                      const CRiskAwareReactiveNav& probe) const {
    const auto& pr = probe.params_reactive_nav;
    const double z = world.laser.options.z;
    const std::string sec = "CReactiveNavigationSystem";
    const bool low = z < pr.min_obstacles_height;
    if (low || z > pr.max_obstacles_height) {
        const std::string key = low ? "min_obstacles_height" : "max_obstacles_height";
        const mrpt::config::CConfigFileBase& holder =
            m_engine && !c.keyExists(sec, key)
                ? static_cast<const mrpt::config::CConfigFileBase&>(*m_engine)
                : c;
        throwBadKey(holder, sec, key, holder.read_string(sec, key, ""),
                    std::string("the laser is mounted ") + (low ? "below" : "above") +
                        " it ([" + world.laser.options.section +
                        "] z = " + numberText(z) +
                        " m): MRPT would drop every obstacle point it senses");
    }
}

void CNavigationRun::checkLimiterInputs(const CIniConfig& c,
                                        const CRiskAwareReactiveNav& probe) const {
    // a second sensor the adaptive limiter is to fuse must exist
    for (const auto& l : probe.limiters())
        if (const auto* a = dynamic_cast<const CAdaptiveSpeedLimiter*>(l.get());
            a && a->options.use_range2 && !world.range2.options.enabled)
            throwBadKey(c, "CAdaptiveSpeedLimiter", "use_range2",
                        c.read_string("CAdaptiveSpeedLimiter", "use_range2", "true"),
                        "the world has no second range sensor ([RangeSensor2] "
                        "enabled is false): every cell would stay undecided and the "
                        "robot creep; set use_range2 = false or enable it");
    // A learned afraid map is for one map: its grid must be the world's.
    for (const auto& l : probe.limiters())
        if (const auto* a = dynamic_cast<const CAfraidSpeedLimiter*>(l.get())) {
            const auto& g = a->grid();
            const auto& m = world.grid();
            const double res = m.getResolution();
            if (g.sizeX() != int(m.getSizeX()) || g.sizeY() != int(m.getSizeY()) ||
                std::abs(g.resolution() - res) > 1e-9 ||
                std::abs(g.xMin() - m.getXMin()) > 0.5 * res ||
                std::abs(g.yMin() - m.getYMin()) > 0.5 * res) {
                char b[300];
                std::snprintf(b, sizeof(b),
                              "its grid (%d x %d cells of %.3f m from (%.2f, %.2f)) is "
                              "not the world map's (%u x %u of %.3f m from (%.2f, %.2f))",
                              g.sizeX(), g.sizeY(), g.resolution(), g.xMin(), g.yMin(),
                              m.getSizeX(), m.getSizeY(), res, m.getXMin(), m.getYMin());
                throwBadKey(c, "CAfraidSpeedLimiter", "afraid_file",
                            a->options.afraid_file, b);
            }
        }
}

// Only the limiters named are read; the sections of the others must
// not be silently ignored.
void CNavigationRun::checkSectionsKnown(
    CIniConfig& c, const CRiskAwareReactiveNav& probe,
    const std::vector<std::string>& otherSections) const {
    std::set<std::string> known(kEngineSections);
    for (const auto* s : {"Navigate", "World", "Robot", "Odometry", "Laser",
                          "RangeSensor2", "CRiskAwareReactiveNav"})
        known.insert(s);
    if (options.global_planner != "none")
        known.insert("GlobalPlanner");
    if (options.localization == "mcl")
        for (const auto* s :
             {"Localization", "PF_options", "KLD_options", "LostLocalization"})
            known.insert(s);
    for (const auto& n : probe.riskOptions.speed_limiters)
        known.insert(n.substr(n.rfind(':') == std::string::npos ? 0 : n.rfind(':') + 1));
    for (const auto& s : otherSections)
        known.insert(s);
    std::vector<std::string> checked;
    for (const auto& s : c.sections()) {
        // A section a limiter read (e.g. the sensor models the adaptive
        // limiter's laser_model names) is known too.
        std::vector<std::string> keys;
        c.getAllKeys(s, keys);
        const bool readByPlugin = c.unreadKeys({s}).size() < keys.size();
        if (!known.count(s) && !sim::CAgentsSim::ownsSection(s) && !readByPlugin)
            c.throwUnknownSection(
                s,
                "Navigate, World, Robot, Odometry, Laser, RangeSensor2, "
                "people and clutter, CRiskAwareReactiveNav, GlobalPlanner (with "
                "global_planner = grid or risk) and the sections of the "
                "limiters it names, MRPT's engine sections" +
                    std::string(options.localization == "mcl"
                                    ? ", Localization, PF_options, KLD_options, "
                                      "LostLocalization"
                                    : ""));
        if (!kEngineSections.count(s) &&
            std::find(otherSections.begin(), otherSections.end(), s) ==
                otherSections.end())
            checked.push_back(s);
    }
    // MRPT's sections: MRPT reads only those of the methods chosen (a
    // config with [CHolonomicND] for another method still works), but in
    // a section it did read, a key it did not is a typo.
    for (const auto& s : c.sections())
        if (kEngineSections.count(s)) {
            std::vector<std::string> keys;
            c.getAllKeys(s, keys);
            const bool readHere = c.unreadKeys({s}).size() < keys.size();
            bool readThere = false;
            if (m_engine && m_engine->sectionExists(s)) {
                std::vector<std::string> ek;
                m_engine->getAllKeys(s, ek);
                readThere = m_engine->unreadKeys({s}).size() < ek.size();
            }
            if (readHere || readThere)
                checked.push_back(s);
        }
    c.throwOnUnreadKeys(checked);
}

void CNavigationRun::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    options.saveToConfigFile(c, kSec);
    if (options.global_planner != "none")
        plannerOptions.saveToConfigFile(c, "GlobalPlanner");
    if (options.global_planner == "risk")
        m_propagation.saveToConfigFile(c, "Odometry");
    world.saveToConfigFile(c);
    if (options.localization == "mcl") {
        mcl.saveToConfigFile(c);
        mcl.lostOptions.saveToConfigFile(c, "LostLocalization");
    }
    copyConfigKeys(m_navigatorConfig, c);
}

void CNavigationRun::loadRoute(CIniConfig& c) {
    waypoints = {};
    tags.clear();
    const double tol = options.goal_tolerance;
    if (!options.goals.empty()) {
        routeName = "goals";
        for (size_t i = 0; i + 1 < options.goals.size(); i += 2)
            waypoints.waypoints.emplace_back(options.goals[i], options.goals[i + 1], tol,
                                             false);
        return;
    }
    if (!options.route_file.empty()) {
        routeName = options.route_file;
        readWaypointFile(options.route_file, tol, waypoints, tags);
        return;
    }
    // risk_config: the risk evaluator's ranking, evaluated here.
    risk::CRiskEvaluator ev;
    CIniConfig rc(options.risk_config);
    ev.loadFromConfigFile(rc);
    ev.evaluate();
    // Its routes are planned for its map and start: the world's must be the
    // same (an .afraid file is checked the same way), or U means nothing here.
    {
        const auto& a = ev.grid();
        const auto& b = world.grid();
        const bool sameGeometry =
            a.getSizeX() == b.getSizeX() && a.getSizeY() == b.getSizeY() &&
            std::abs(a.getResolution() - b.getResolution()) < 1e-9 &&
            std::abs(a.getXMin() - b.getXMin()) < 1e-6 &&
            std::abs(a.getYMin() - b.getYMin()) < 1e-6;
        size_t differ = 0;
        if (sameGeometry)
            for (unsigned y = 0; y < a.getSizeY(); y++)
                for (unsigned x = 0; x < a.getSizeX(); x++)
                    differ += (a.getCell(int(x), int(y)) < 0.5) !=
                              (b.getCell(int(x), int(y)) < 0.5);
        if (!sameGeometry || differ > 0) {
            char why[240];
            std::snprintf(why, sizeof(why),
                          "its map (%u x %u cells of %.3g m from (%.3g, %.3g)) is not "
                          "[World]'s (%u x %u of %.3g m from (%.3g, %.3g))%s",
                          a.getSizeX(), a.getSizeY(), a.getResolution(), a.getXMin(),
                          a.getYMin(), b.getSizeX(), b.getSizeY(), b.getResolution(),
                          b.getXMin(), b.getYMin(),
                          sameGeometry ? ": the same grid, other walls" : "");
            throwBadKey(c, kSec, "risk_config", options.risk_config, why);
        }
        const auto& s0 = ev.options.start;
        if (std::hypot(s0.x - options.start.x, s0.y - options.start.y) >
            options.goal_tolerance)
            throwBadKey(c, kSec, "start", readString(c, kSec, "start", ""),
                        "the risk evaluator's routes start at " + pointText(s0.x, s0.y) +
                            " (" + options.risk_config +
                            "), more than goal_tolerance away");
    }
    const auto& rows = ev.rows();
    long pick = -1;
    if (options.risk_route == "best")
        pick = ev.best();
    else if (options.risk_route == "worst") {
        for (size_t i = 0; i < rows.size(); i++)
            if (!rows[i].excluded && rows[i].feasible &&
                (pick < 0 || rows[i].result.U > rows[size_t(pick)].result.U))
                pick = long(i);
    } else {
        std::string names;
        for (size_t r = 0; r < ev.routes().size(); r++) {
            names += (names.empty() ? "" : ", ") + ev.routes()[r].name;
            if (ev.routes()[r].name == options.risk_route)
                pick = long(&ev.plainRow(r) - rows.data());
        }
        if (pick < 0)
            throwBadKey(c, kSec, "risk_route", options.risk_route,
                        "no such route in " + options.risk_config + " (routes: " + names +
                            "; or best, worst)");
        // a route the evaluator ruled out is not driven (its U is no score)
        const auto& named = rows[size_t(pick)];
        if (named.excluded || !named.feasible || !std::isfinite(named.result.U))
            throwBadKey(
                c, kSec, "risk_route", options.risk_route,
                "the risk evaluator excluded this route (" +
                    (named.reason.empty() ? std::string("not feasible") : named.reason) +
                    ")");
    }
    if (pick < 0)
        throwBadKey(c, kSec, "risk_config", options.risk_config,
                    "the risk evaluator found no usable route");
    const auto& row = rows[size_t(pick)];
    routeName = ev.routes()[row.route].name + " (" + ev.sensingName(row) +
                ", U = " + numberText(row.result.U) + ")";
    for (size_t i = 1; i < row.path.size(); i++)
        waypoints.waypoints.emplace_back(row.path[i].x, row.path[i].y, tol, false);
    for (size_t s : row.sensing) {
        const auto& sp = ev.sensingPoints[s];
        size_t best = 0;
        double bestD = 1e300;
        for (size_t i = 0; i < waypoints.waypoints.size(); i++) {
            const double d = std::hypot(waypoints.waypoints[i].target.x - sp.x,
                                        waypoints.waypoints[i].target.y - sp.y);
            if (d < bestD)
                bestD = d, best = i;
        }
        tags[best] = {"sensing", sp.name, sp.sigma_x, sp.sigma_y,
                      sp.sigma_theta_deg * M_PI / 180.0};
    }
}

void CNavigationRun::checkAgainstMap(const CIniConfig& c) const {
    const auto& g = world.grid();
    auto onMap = [&](double x, double y) {
        return x >= g.getXMin() && x <= g.getXMax() && y >= g.getYMin() &&
               y <= g.getYMax();
    };
    const auto& s = options.start;
    const std::string startText = readString(c, kSec, "start", "");
    if (!onMap(s.x, s.y))
        throwBadKey(c, kSec, "start", startText,
                    "start " + pointText(s.x, s.y) + " is outside the map");
    // the map and the clutter the map does not hold, in metres, as every app
    // checks a start (CSimWorld::placement()); people move: a person crossing
    // the start is the world's, not the config's, problem
    if (const auto pl = world.placement(s.x, s.y); !pl.free())
        throwBadKey(c, kSec, "start", startText,
                    "the robot is spawned in collision with " + pl.with + ": start " +
                        pointText(s.x, s.y) + " " + pl.why);
    // the people's paths and the clutter against the map (as risknav-simulate)
    world.checkAgentsAgainstMap(c);
    for (const auto& w : waypoints.waypoints) {
        const bool inside = onMap(w.target.x, w.target.y);
        if (!inside || world.pointClearance(w.target.x, w.target.y) <= 0)
            throwBadKey(
                c, kSec,
                !options.goals.empty()
                    ? "goals"
                    : (!options.route_file.empty() ? "route_file" : "risk_config"),
                !options.goals.empty() ? readString(c, kSec, "goals", "") : routeName,
                "waypoint " + pointText(w.target.x, w.target.y) +
                    (inside ? " is inside an obstacle of the map"
                            : " is outside the map"));
    }
}

mrpt::nav::TWaypointSequence CNavigationRun::lapWaypoints(int laps) const {
    mrpt::nav::TWaypointSequence out;
    const auto& w = waypoints.waypoints;
    out.waypoints = w;
    if (options.mode == "once")
        return out;
    const mrpt::nav::TWaypoint start(options.start.x, options.start.y,
                                     options.goal_tolerance, false);
    for (int lap = 1; lap < laps; lap++) {
        if (options.mode == "loop") {
            out.waypoints.push_back(start);
            out.waypoints.insert(out.waypoints.end(), w.begin(), w.end());
        } else {  // back_and_forth: back along the route, then out again
            for (size_t i = w.size() - 1; i-- > 0;)
                out.waypoints.push_back(w[i]);
            out.waypoints.push_back(start);
            if (++lap >= laps)
                break;
            out.waypoints.insert(out.waypoints.end(), w.begin(), w.end());
        }
    }
    return out;
}

std::string CNavigationRun::ptgCacheDir() const {
    if (!options.ptg_cache_dir.empty())
        return options.ptg_cache_dir;
    return (fs::temp_directory_path() / "risknav-ptg-cache").string();
}

mrpt::math::CPolygon CNavigationRun::robotShape() const {
    // the 24-gon around the world's robot disc grown by shape_margin (vertices
    // at (R + margin) / cos(pi / 24)), so that MRPT's collision checks cover
    // the disc the safety monitor measures
    mrpt::math::CPolygon shape;
    const double rv = (world.robot.radius + options.shape_margin) / std::cos(M_PI / 24);
    for (int i = 0; i < 24; i++)
        shape.AddVertex(rv * std::cos(i * M_PI / 12), rv * std::sin(i * M_PI / 12));
    return shape;
}

}  // namespace risknav::nav
