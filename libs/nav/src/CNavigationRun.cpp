#include <risknav/common/CAppRunner.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/CProgress.h>
#include <risknav/common/CSpeedLimiter.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CLayeredConfig.h>
#include <risknav/nav/CNavigationRun.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/risk/CRiskEvaluator.h>
#include <risknav/sim/CRawlogWriter.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/kinematics/CVehicleSimul_DiffDriven.h>
#include <mrpt/math/CPolygon.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/nav/reactive/CRobot2NavInterfaceForSimulator.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/filesystem.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <set>
#include <sstream>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
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

// The message of an error MRPT logged: after its "Message:" header, the
// first line.
std::string mrptErrorText(std::string m) {
    const auto p = m.find("Message:");
    if (p != std::string::npos)
        m = m.substr(p + 8);
    const auto b = m.find_first_not_of(" \n");
    return firstLine(b == std::string::npos ? m : m.substr(b));
}

// The scoped simulated clock: MRPT's navigator times itself on mrpt::Clock.
struct TSimClock {
    explicit TSimClock(double t0) {
        mrpt::Clock::setSimulatedTime(mrpt::Clock::fromDouble(t0));
        mrpt::Clock::setActiveClock(mrpt::Clock::Simulated);
    }
    ~TSimClock() { mrpt::Clock::setActiveClock(mrpt::Clock::Realtime); }
    void set(double t) { mrpt::Clock::setSimulatedTime(mrpt::Clock::fromDouble(t)); }
};
// MRPT names its PTG grid files by PTG index only (ReacNavGrid_000...):
// runs of other PTGs or shapes sharing one folder rebuilt and overwrote each
// other's files, and one run read another's half-written file (an
// allocation of 12-24 GB, killed; found when CI's parallel tests started
// with no cache). So one subfolder per set of PTGs (the engine's
// [CReactiveNavigationSystem] keys as it loaded them) and robot shape (the
// polygon's vertex radius `rv`), named by their FNV-1a hash (the same name
// in every build).
std::string ptgSetName(const mrpt::config::CConfigFileBase& engine, double rv) {
    std::vector<std::string> keys;
    engine.getAllKeys("CReactiveNavigationSystem", keys);
    std::sort(keys.begin(), keys.end());
    std::string text;
    for (const auto& k : keys)
        text += k + "=" + engine.read_string("CReactiveNavigationSystem", k, "") + "\n";
    text += "shape=" + numberText(rv) + "\n";
    uint64_t h = 1469598103934665603ull;
    for (const unsigned char ch : text)
        h = (h ^ ch) * 1099511628211ull;
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

/** An exclusive flock on a file (created if need be) for its lifetime; no
 * lock when the file cannot be opened (the work then runs unguarded). */
struct TFileLock {
    explicit TFileLock(const std::string& path)
        : fd(::open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
        if (fd >= 0)
            ::flock(fd, LOCK_EX);
    }
    ~TFileLock() {
        if (fd >= 0)
            ::close(fd);
    }
    TFileLock(const TFileLock&) = delete;
    TFileLock& operator=(const TFileLock&) = delete;
    int fd;
};
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
    // The outputs, bounded before the run starts (a 1e5 s run that
    // never arrived was on its way to ~28 GB of navlog, ~56 KB a cycle): at
    // most 36,000 navlog cycles (2 h at 0.2 s, ~2 GB) and a rawlog of at most
    // 5e8 ranges (~2 GB, as risknav-simulate); one frame a cycle
    {
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

    // The engine and the limiters, through a navigator that never runs: an
    // unknown limiter, a missing section or key, a bad .afraid file, or a
    // config MRPT refuses are all exit 2 here, before any output.
    {
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
        // MRPT keeps only the obstacle points within [min, max] of these
        // heights: the laser's own height outside them is a blind robot
        {
            const auto& pr = probe.params_reactive_nav;
            const double z = world.laser.options.z;
            const std::string sec = "CReactiveNavigationSystem";
            const bool low = z < pr.min_obstacles_height;
            if (low || z > pr.max_obstacles_height) {
                const std::string key =
                    low ? "min_obstacles_height" : "max_obstacles_height";
                const mrpt::config::CConfigFileBase& holder =
                    m_engine && !c.keyExists(sec, key)
                        ? static_cast<const mrpt::config::CConfigFileBase&>(*m_engine)
                        : c;
                throwBadKey(holder, sec, key, holder.read_string(sec, key, ""),
                            std::string("the laser is mounted ") +
                                (low ? "below" : "above") + " it ([" +
                                world.laser.options.section + "] z = " + numberText(z) +
                                " m): MRPT would drop every obstacle point it senses");
            }
        }
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
                    std::snprintf(
                        b, sizeof(b),
                        "its grid (%d x %d cells of %.3f m from (%.2f, %.2f)) is "
                        "not the world map's (%u x %u of %.3f m from (%.2f, %.2f))",
                        g.sizeX(), g.sizeY(), g.resolution(), g.xMin(), g.yMin(),
                        m.getSizeX(), m.getSizeY(), res, m.getXMin(), m.getYMin());
                    throwBadKey(c, "CAfraidSpeedLimiter", "afraid_file",
                                a->options.afraid_file, b);
                }
            }
        // Only the limiters named are read; the sections of the others must
        // not be silently ignored.
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
            known.insert(
                n.substr(n.rfind(':') == std::string::npos ? 0 : n.rfind(':') + 1));
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

// MRPT failing on each of this many first cycles of a run: a config error
// if it fails so in open space too (engineFailsInOpenSpace()).
constexpr int kFailedCyclesForBadConfig = 5;

namespace {
/** MRPT's own simulated differential robot with a laser that senses
 * nothing: open space. */
class COpenSpaceRobot : public mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven {
  public:
    using CRobot2NavInterfaceForSimulator_DiffDriven::
        CRobot2NavInterfaceForSimulator_DiffDriven;
    bool senseObstacles(mrpt::maps::CSimplePointsMap& obstacles,
                        mrpt::system::TTimeStamp& timestamp) override {
        obstacles.clear();
        timestamp = mrpt::Clock::now();
        return true;
    }
};
}  // namespace

std::string CNavigationRun::engineFailsInOpenSpace(const std::string& cacheDir,
                                                   double clockNow) const {
    // the engine as configured, without the limiters (they may need the
    // world), on MRPT's simulated robot in open space, 3 m to a target
    // straight ahead: the cycles a config error fails on wherever it is
    mrpt::config::CConfigFileMemory noLimiters;
    noLimiters.write("CRiskAwareReactiveNav", "speed_limiters", "");
    const CLayeredConfig layered(noLimiters, *m_cfg);
    mrpt::kinematics::CVehicleSimul_DiffDriven vehicle;
    vehicle.setCurrentGTPose(mrpt::math::TPose2D(0, 0, 0));
    COpenSpaceRobot robot(vehicle);
    robot.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    CRiskAwareReactiveNav nav(robot);
    nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    nav.logging_enable_console_output = false;
    int errors = 0;
    std::string first;
    nav.logRegisterCallback([&](std::string_view msg, mrpt::system::VerbosityLevel lvl,
                                std::string_view, mrpt::Clock::time_point) {
        if (lvl < mrpt::system::LVL_ERROR)
            return;
        errors++;
        if (first.empty())
            first = mrptErrorText(std::string(msg));
    });
    const_cast<mrpt::system::CTimeLogger&>(nav.getDelaysTimeLogger()).disable();
    nav.setEngineConfig(m_engine.get());
    try {
        nav.loadConfigFile(layered);
        nav.params_abstract_ptg_navigator.ptg_cache_files_directory = cacheDir;
        nav.changeRobotShape(robotShape());
        {
            const TFileLock lock((fs::path(cacheDir) / ".lock").string());
            nav.initialize();
        }
        mrpt::nav::CAbstractNavigator::TNavigationParams np;
        np.target.target_coords = mrpt::math::TPose2D(3, 0, 0);
        np.target.targetAllowedDistance = options.goal_tolerance;
        nav.navigate(&np);
        double t = clockNow;
        for (int k = 0; k < kFailedCyclesForBadConfig; k++) {
            const int before = errors;
            nav.navigationStep();
            if (errors == before)
                return "";
            t += options.nav_period;
            vehicle.simulateOneTimeStep(options.nav_period);
            mrpt::Clock::setSimulatedTime(mrpt::Clock::fromDouble(t));
        }
    } catch (const std::exception& e) {
        return firstLine(e.what());
    }
    return first.empty() ? std::string("(no message)") : first;
}

TNavRunResult CNavigationRun::run(const TNavRunSetup& setup) {
    const auto wall0 = std::chrono::steady_clock::now();
    if (!m_cfg)
        throw std::logic_error("CNavigationRun::run() before loadFromConfigFile()");
    CIniConfig& c = *m_cfg;
    if (setup.limiters) {
        std::string list;
        for (const auto& n : *setup.limiters)
            list += (list.empty() ? "" : " ") + n;
        c.write("CRiskAwareReactiveNav", "speed_limiters", list);
    }
    // absolute: a relative key is read relative to the config's folder, while
    // the caller's path (e.g. a staged output under a relative --out) is
    // relative to the working directory
    if (setup.afraidFile)
        c.write("CAfraidSpeedLimiter", "afraid_file",
                fs::absolute(*setup.afraidFile).string());

    TNavRunResult r;
    world.reset(options.start, setup.seed, options.start_time);
    sim::CSimRobotInterface robotIf(world);
    robotIf.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    const bool navlog = !setup.navlogDir.empty();
    if (navlog)
        fs::create_directories(setup.navlogDir);
    CRiskAwareReactiveNav nav(robotIf, false, false, navlog ? setup.navlogDir : ".");
    nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    // MRPT's errors (e.g. exceptions it catches inside navigationStep()) are
    // counted for summary.json instead of flooding the terminal.
    nav.logging_enable_console_output = false;
    // the last error's text, for its mrpt_error event (when and where)
    std::string lastMrptError;
    int mrptErrorsSeen = 0;
    // MRPT's navlog writer failing (a full disk) is not a value of the
    // config: the system's reason, as the failed write left it
    int navlogWriteErrno = 0;
    nav.logRegisterCallback([&r, &lastMrptError, &navlogWriteErrno](
                                std::string_view msg, mrpt::system::VerbosityLevel lvl,
                                std::string_view, mrpt::Clock::time_point) {
        const int err = errno;
        if (lvl < mrpt::system::LVL_ERROR)
            return;
        if (msg.find("Cannot write bytes to stream") != std::string_view::npos &&
            !navlogWriteErrno)
            navlogWriteErrno = err ? err : EIO;
        r.mrptErrors++;
        lastMrptError = mrptErrorText(std::string(msg));
        if (r.firstMrptError.empty())
            r.firstMrptError = lastMrptError;
    });
    const_cast<mrpt::system::CTimeLogger&>(nav.getDelaysTimeLogger()).disable();
    nav.setEngineConfig(m_engine.get());
    if (m_planner) {
        m_planner->resetFollowing();
        nav.setGlobalPlanner(m_planner);
    }
    nav.loadConfigFile(c);
    if (setup.maxSpeed)
        nav.changeCurrentRobotSpeedLimits().robotMax_V_mps = *setup.maxSpeed;
    // The world's robot is a disc: MRPT gets the 24-gon around it.
    const mrpt::math::CPolygon shape = robotShape();
    const std::string cacheDir =
        (fs::path(ptgCacheDir()) / ptgSetName(m_navigatorConfig, shape[0].x)).string();
    nav.params_abstract_ptg_navigator.ptg_cache_files_directory = cacheDir;
    {
        // MRPT writes its PTG grids there: a file, or a folder that cannot
        // be written, is the key's error (not a filesystem exception)
        const std::string dir = cacheDir;
        std::error_code ec;
        fs::create_directories(dir, ec);
        bool ok = !ec && fs::is_directory(dir, ec);
        if (ok) {
            const fs::path probe =
                fs::path(dir) / (".risknav-write-probe." + std::to_string(getpid()));
            ok = bool(std::ofstream(probe));
            fs::remove(probe, ec);
        }
        if (!ok)
            throwBadKey(c, "Navigate", "ptg_cache_dir", ptgCacheDir(),
                        "cannot create or write this directory (MRPT's PTG cache)");
    }
    nav.changeRobotShape(shape);
    {
        // one run at a time builds or reads a subfolder's grids (MRPT writes
        // them in place, not atomically)
        const TFileLock lock((fs::path(cacheDir) / ".lock").string());
        // MRPT prints an unreadable grid file's exception with its backtrace
        // to std::cerr (18 lines, even with -q) and then rebuilds the grid:
        // caught here and told in one line
        std::ostringstream mrptSaid;
        struct TCerrTo {
            std::streambuf* old;
            explicit TCerrTo(std::ostream& o) : old(std::cerr.rdbuf(o.rdbuf())) {}
            ~TCerrTo() { std::cerr.rdbuf(old); }
        };
        try {
            const TCerrTo redirect(mrptSaid);
            nav.initialize();
        } catch (const std::exception& e) {
            // values MRPT checks only as it builds its PTGs (e.g.
            // CPTG_Holo_Blend's T_ramp_max or expr_V): its refusal of the config
            throw CBadInputError(
                (m_engine ? m_engine->path() + " (engine_config) + " : "") +
                m_cfg->path() +
                ": MRPT's reactive engine refused the config as it built its PTGs: " +
                clippedText(firstLine(e.what())));
        }
        if (!mrptSaid.str().empty() && !setup.quiet)
            std::cerr << "risknav-navigate: note: MRPT rebuilt a PTG grid of " << cacheDir
                      << " (" << firstLine(mrptSaid.str()) << ")\n";
    }
    if (navlog) {
        nav.setLogFileDirectory(setup.navlogDir);
        nav.enableLogFile(true);
        nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    }

    auto wps = lapWaypoints(setup.laps.value_or(options.laps));
    // the end is aimed at within arrival_radius, judged against its own
    // allowed distance (see TNavigateOptions::arrival_radius)
    const double goalAllowed =
        wps.waypoints.empty() ? 0.0 : wps.waypoints.back().allowed_distance;
    if (!wps.waypoints.empty()) {
        // a goal nearer an obstacle than MRPT's disc: its centre stops
        // disc - clearance short of it at best; asked within that + 0.1 m
        // (still at most the goal's own allowed distance), not within
        // arrival_radius it cannot come to
        auto& end = wps.waypoints.back();
        const double disc = world.robot.radius + options.shape_margin;
        const double clear =
            world.distanceField().pointClearance(end.target.x, end.target.y, disc + 0.2);
        const double shortOf = std::max(0.0, disc - clear);
        end.allowed_distance =
            std::min(goalAllowed, std::max(options.arrival_radius, shortOf + 0.1));
    }
    r.waypointCount = int(wps.waypoints.size());
    const size_t lapLen = waypoints.waypoints.size();
    auto tagOf = [&](int i) -> const TWaypointTag* {
        if (i < 0 || lapLen == 0 || options.mode != "once")
            return nullptr;  // tags of laps beyond the first: the route's order
        const auto it = tags.find(size_t(i));
        return it == tags.end() ? nullptr : &it->second;
    };

    std::unique_ptr<sim::CRawlogWriter> rawlog;
    std::ofstream gt;
    if (!setup.rawlogPath.empty())
        rawlog = std::make_unique<sim::CRawlogWriter>(setup.rawlogPath);
    if (!setup.groundtruthPath.empty()) {
        gt.open(setup.groundtruthPath);
        gt << "% t x y phi  (ground truth at each rawlog frame; t = UNIX time [s], phi "
              "[rad])\n";
    }
    const bool useMcl = options.localization == "mcl";
    if (useMcl) {
        mcl.options.initPose = options.start;
        mcl.initialize(world.grid(), setup.seed);
    }
    mrpt::poses::CPose2D odoFix;  // believed = odoFix (+) odometry (odometry mode)
    // The odoFix that makes the belief `pose` now: believed = odoFix (+) odo
    // must equal it, so odoFix = pose (+) (-odo). (MRPT's binary "pose - odo"
    // is the inverse composition (-odo) (+) pose, the pose seen from the
    // odometry frame: composed on the left it would rotate the whole
    // odometry track about the world origin by the heading correction, a
    // jump of |odo| * dtheta.)
    auto odoFixFor = [&](const TPose2D& pose) {
        return mrpt::poses::CPose2D(pose) +
               (-mrpt::poses::CPose2D(world.odometricPose()));
    };
    std::mt19937_64 fixRng(setup.seed ^ 0x5EED5EEDull);
    const auto& ss = options.start_sigma;
    if (options.localization == "odometry" && (ss[0] > 0 || ss[1] > 0 || ss[2] > 0)) {
        // The belief starts off by an error drawn with start_sigma (the
        // risk evaluator's init_sigma_*), its own generator so that the
        // sensing fixes draw the same numbers with or without it.
        std::mt19937_64 startRng(setup.seed ^ 0x57A27E22ull);
        std::normal_distribution<double> n(0, 1);
        const double ex = ss[0] * n(startRng), ey = ss[1] * n(startRng),
                     ephi = ss[2] * n(startRng);
        odoFix = odoFixFor(TPose2D(options.start.x + ex, options.start.y + ey,
                                   options.start.phi + ephi));
    }
    TPose2D lastOdo = world.odometricPose();
    TPose2D believed = options.start;

    nav.navigateWaypoints(wps);
    const double dt = options.sim_dt;
    const int stepsPerCycle = int(std::lround(options.nav_period / dt));
    const double t0 = options.start_time;
    TSimClock clock(t0);
    CProgress progress(setup.label.empty() ? "navigate" : setup.label,
                       size_t(options.duration_max), "s", setup.quiet);
    size_t eventsSeen = 0;
    r.track.emplace_back(world.truePose().x, world.truePose().y);
    // where and when the robot last moved stall_distance away (stall_timeout)
    mrpt::math::TPoint2D stallSpot(world.truePose().x, world.truePose().y);
    double stallSince = world.time();
    bool everyCycleFailed = true;
    size_t plansSeen = 0;  // the planner's (re)plans already taken in
    for (int cycle = 0;; cycle++) {
        const double t = world.time();
        const auto& scans = robotIf.senseNow();
        const TPose2D truth = world.truePose(), odo = world.odometricPose();
        mrpt::obs::CActionCollection acts;
        mrpt::obs::CActionRobotMovement2D mv;
        mv.timestamp = world.timestamp();
        mv.computeFromOdometry(mrpt::poses::CPose2D(odo) - mrpt::poses::CPose2D(lastOdo),
                               mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
        acts.insert(mv);
        mrpt::obs::CSensoryFrame sf;
        sf.insert(scans.laser);
        if (scans.range2)
            sf.insert(scans.range2);
        lastOdo = odo;
        if (useMcl) {
            believed = mcl.step(acts, sf).mean;
            // a filter whose scan no longer fits the map (or spread out) for
            // lost_after cycles is lost: told, and re-spread about its mean
            // (MCL's standard recovery), never a success by itself
            const auto chk = mcl.checkLost(sf);
            if (chk.lost) {
                r.localizationLost++;
                char b[200];
                std::snprintf(b, sizeof(b),
                              "%s (scan fit %.2f, spread %.2f m / %.0f deg; true error "
                              "%.2f m): particles re-spread about the mean",
                              chk.reason.c_str(), chk.fitFraction, chk.spreadXY,
                              chk.spreadPhiDeg,
                              std::hypot(believed.x - world.truePose().x,
                                         believed.y - world.truePose().y));
                r.events.push_back(TNavRunEvent{t, "localization_lost", -1,
                                                world.truePose().x, world.truePose().y,
                                                b});
                mcl.recover();
            }
        } else if (options.localization == "odometry")
            believed = (odoFix + mrpt::poses::CPose2D(odo)).asTPose();
        else
            believed = truth;
        robotIf.setLocalization(options.localization == "ground_truth"
                                    ? std::nullopt
                                    : std::optional<TPose2D>(believed));
        if (rawlog) {
            rawlog->write(acts, sf);
            r.rawlogFrames = rawlog->frames();
        }
        if (gt) {
            char b[128];
            std::snprintf(b, sizeof(b), "%.3f %.6f %.6f %.6f\n", t0 + t, truth.x, truth.y,
                          truth.phi);
            gt << b;
        }

        const auto s0 = std::chrono::steady_clock::now();
        nav.navigationStep();
        const double stepS =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - s0).count();
        r.navStepSeconds += stepS;
        if (m_planner && m_planner->replans().size() > plansSeen) {
            plansSeen = m_planner->replans().size();
            const auto& cur = m_planner->current();
            if (cur.found && (r.planPaths.empty() || r.planPaths.back() != cur.points)) {
                if (r.planPaths.empty())
                    r.firstPlanLength = cur.length;
                r.planPaths.push_back(cur.points);
            }
        }

        TNavCycle rec;
        rec.cycle = cycle;
        rec.t = t;
        rec.truePose = truth;
        rec.believedPose = believed;
        rec.poseError = std::hypot(believed.x - truth.x, believed.y - truth.y);
        rec.speed = world.speed();
        rec.command = world.commandedSpeed();
        const auto& lim = nav.lastLimit();
        rec.desired = lim.desired;
        rec.limit = lim.limit;
        rec.limiter =
            lim.unsticking ? "unstick" : (lim.turning ? "turn_in_place" : lim.limiter);
        rec.reason = lim.reason;
        rec.clearance = world.pointClearance(truth.x, truth.y) - world.robot.radius;
        rec.waypoint = nav.getWaypointNavStatus().waypoint_index_current_goal;
        rec.distance = r.distance;
        rec.stepMs = 1e3 * stepS;
        r.maxPoseError = std::max(r.maxPoseError, rec.poseError);
        if (!wps.waypoints.empty() && rec.waypoint == int(wps.waypoints.size()) - 1) {
            const auto& g = wps.waypoints.back().target;
            r.goalTrueDistance =
                std::min(r.goalTrueDistance, std::hypot(truth.x - g.x, truth.y - g.y));
        }
        r.cycles.push_back(rec);

        // The navigator's events of this step, and what tagged waypoints do.
        const auto& ev = robotIf.navEvents();
        for (; eventsSeen < ev.size(); eventsSeen++) {
            const auto& e = ev[eventsSeen];
            TNavRunEvent out{e.t, e.kind, e.waypoint, truth.x, truth.y, ""};
            if (e.kind == "waypoint_reached")
                r.waypointsReached++;
            if (e.kind == "waypoint_skipped")
                r.waypointsSkipped++;
            r.events.push_back(out);
            const TWaypointTag* tag =
                e.kind == "waypoint_reached" ? tagOf(e.waypoint) : nullptr;
            if (!tag)
                continue;
            TNavRunEvent te{e.t, tag->kind, e.waypoint, truth.x, truth.y, tag->detail};
            if (tag->kind == "sensing" && options.localization == "odometry") {
                // The paper's sensing point: the pose is measured there with the
                // point's sigmas (001 section 5.2), so the belief is reset.
                std::normal_distribution<double> n(0, 1);
                const TPose2D fix(truth.x + tag->sigmaX * n(fixRng),
                                  truth.y + tag->sigmaY * n(fixRng),
                                  truth.phi + tag->sigmaPhi * n(fixRng));
                odoFix = odoFixFor(fix);
                char b[120];
                std::snprintf(b, sizeof(b), "%s: pose fixed (error before %.3f m)",
                              tag->detail.c_str(), rec.poseError);
                te.detail = b;
            }
            r.events.push_back(te);
        }
        if (navlogWriteErrno && navlog)
            throw writeFailure(setup.navlogDir + "/navigation.reactivenavlog",
                               navlogWriteErrno);
        // MRPT failing on each of the run's first cycles (exceptions it
        // catches inside navigationStep(), e.g. its asserts on a PTG's
        // clearance_num_points, a v_max_mps of 1e-9 or a score formula
        // whose variable its PTG never sets: the robot never moved, exit 0)
        // is a value of its config that MRPT takes without a check
        const bool failedNow = r.mrptErrors > mrptErrorsSeen;
        everyCycleFailed = everyCycleFailed && failedNow;
        if (everyCycleFailed && cycle + 1 == kFailedCyclesForBadConfig) {
            // A config error fails so anywhere; a start MRPT's PTGs find no
            // motion from (beside a wall, the target off to the side) is
            // the run's outcome, not the config's: told in summary.json
            const std::string open = engineFailsInOpenSpace(cacheDir, world.time() + t0);
            clock.set(t0 + world.time());
            if (!open.empty())
                throw CBadInputError(
                    m_cfg->path() +
                    (m_engine ? " (engine_config " + m_engine->path() + ")" : "") +
                    ": MRPT's reactive engine failed on each of its first " +
                    std::to_string(kFailedCyclesForBadConfig) +
                    " cycles, in open space too (a value of its config it takes without "
                    "a check): " +
                    clippedText(r.firstMrptError));
            r.events.push_back(TNavRunEvent{
                t, "mrpt_error", -1, truth.x, truth.y,
                "MRPT's engine failed on each of the first " +
                    std::to_string(kFailedCyclesForBadConfig) +
                    " cycles here (not in open space: the start's surroundings)"});
        }
        // MRPT's errors of this step (caught inside navigationStep()): one
        // event with their count and the last one's message
        if (failedNow) {
            r.events.push_back(TNavRunEvent{
                t, "mrpt_error", nav.getWaypointNavStatus().waypoint_index_current_goal,
                truth.x, truth.y,
                std::to_string(r.mrptErrors - mrptErrorsSeen) + " x " + lastMrptError});
            mrptErrorsSeen = r.mrptErrors;
        }

        const auto st = nav.getCurrentState();
        if (st == mrpt::nav::CAbstractNavigator::NAV_ERROR) {
            r.status = "navigation_error";
            const auto& er = nav.getErrorReason();
            r.navError = std::to_string(int(er.error_code)) + ": " + er.error_msg;
            if (const auto& f = nav.planFailure()) {
                r.status = "no_path";
                r.noPathFailure = f->failure;
                r.navError = f->failure + ": " + f->reason;
            }
            break;
        }
        if (st == mrpt::nav::CAbstractNavigator::IDLE && cycle > 0 &&
            !nav.requestPending()) {
            r.status = nav.getWaypointNavStatus().final_goal_reached ? "goal_reached"
                                                                     : "stopped";
            break;
        }
        // Not a stall: the target under the robot (its footprint grown by the
        // target's allowed distance), e.g. a viewpoint by a wall that MRPT
        // approaches at mm/s as its obstacle ramp slows it (M4's plan: 45 s).
        // (asked only while the robot is on the spot: it copies MRPT's route)
        auto targetUnder = [&] {
            const auto ct = nav.currentTarget();
            return ct && std::hypot(ct->point.x - believed.x, ct->point.y - believed.y) <=
                             world.robot.radius + ct->allowedDistance;
        };
        if (std::hypot(truth.x - stallSpot.x, truth.y - stallSpot.y) >
                options.stall_distance ||
            targetUnder()) {
            stallSpot = mrpt::math::TPoint2D(truth.x, truth.y);
            stallSince = t;
        } else if (options.stall_timeout > 0 && t - stallSince >= options.stall_timeout) {
            char b[200];
            std::snprintf(b, sizeof(b),
                          "stalled: within %.2f m of (%.2f, %.2f) for %.0f s "
                          "(stall_timeout; MRPT's own alarm did not fire)",
                          options.stall_distance, stallSpot.x, stallSpot.y,
                          t - stallSince);
            r.status = "stalled";
            r.navError = b;
            nav.cancel();
            break;
        }
        if (t >= options.duration_max) {
            r.status = "timeout";
            nav.cancel();
            break;
        }
        r.timePerLimiter[rec.limiter.empty() ? "none" : rec.limiter] +=
            options.nav_period;
        for (const auto& d : world.agents.discs())
            r.people[d.objectId].emplace_back(d.x, d.y);
        for (int k = 0; k < stepsPerCycle; k++) {
            const TPose2D before = world.truePose();
            world.step(dt);
            const TPose2D now = world.truePose();
            r.distance += std::hypot(now.x - before.x, now.y - before.y);
            r.track.emplace_back(now.x, now.y);
            const double tn = world.time();
            r.safety.update(tn, now, world.robot.radius, world.agents,
                            world.pointClearance(now.x, now.y));
            const auto& rb = world.robot;
            // People entering the stopping corridor: the robot cannot stop
            // before them (Choi et al. (002) eqs. 1-5, no beta margin).
            r.safety.updateCorridor(tn, now, world.speed(), rb.radius,
                                    stoppingDistance(world.speed(), rb.t_delay, rb.decel),
                                    rb.radius, world.agents);
        }
        clock.set(t0 + world.time());
        progress.update(size_t(world.time()));
    }
    progress.finish();
    r.time = world.time();
    // the robot's own track between the cycles: MRPT reached the last
    // waypoint when its move passed within the allowed distance
    if (!wps.waypoints.empty() && r.goalTrueDistance < 1e300) {
        const auto& g = wps.waypoints.back().target;
        size_t from = 0;
        for (const auto& cy : r.cycles)
            if (cy.waypoint == int(wps.waypoints.size()) - 1)
                break;
            else
                from += stepsPerCycle;
        for (size_t k = std::min(from, r.track.size()); k < r.track.size(); k++)
            r.goalTrueDistance = std::min(
                r.goalTrueDistance, std::hypot(r.track[k].x - g.x, r.track[k].y - g.y));
    }
    if (r.status == "goal_reached" && !(r.goalTrueDistance <= goalAllowed + 0.03)) {
        char b[300];
        std::snprintf(b, sizeof(b),
                      "MRPT reached the goal on the believed pose, but the robot truly "
                      "came no nearer than %.2f m to it (pose error at the end %.2f m)",
                      r.goalTrueDistance,
                      r.cycles.empty() ? 0.0 : r.cycles.back().poseError);
        r.status = "localization_error";
        r.navError = b;
    }
    if (m_planner) {
        r.plans = m_planner->replans();
        r.routeChoices = m_planner->choices();
        for (const auto& e : r.plans)
            r.events.push_back(TNavRunEvent{
                e.t - t0, e.why == "new_target" ? "plan" : "replan", -1, e.x, e.y,
                e.why + (e.length > 0
                             ? ": " + numberText(std::round(e.length * 100) / 100) + " m"
                             : ": no way")});
        std::stable_sort(
            r.events.begin(), r.events.end(),
            [](const TNavRunEvent& a, const TNavRunEvent& b) { return a.t < b.t; });
    }
    r.finalPoseError = r.cycles.empty() ? 0 : r.cycles.back().poseError;
    r.agentEvents = world.agentEvents();
    // Static clutter is a disc too: keep the tracks of things that moved.
    for (auto it = r.people.begin(); it != r.people.end();) {
        const auto& p = it->second;
        bool moved = false;
        for (const auto& q : p)
            moved |= std::hypot(q.x - p.front().x, q.y - p.front().y) > 0.05;
        it = moved ? std::next(it) : r.people.erase(it);
    }
    if (rawlog)
        rawlog->close();
    if (gt.is_open()) {
        gt.close();
        if (!gt)
            throw std::runtime_error("cannot write " + setup.groundtruthPath);
    }
    if (navlog) {
        nav.enableLogFile(false);  // closes MRPT's file
        for (const auto& e : fs::directory_iterator(setup.navlogDir))
            if (e.path().extension() == ".reactivenavlog")
                r.navlogFile = e.path().string();
    }
    r.wallSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    return r;
}

}  // namespace risknav::nav
