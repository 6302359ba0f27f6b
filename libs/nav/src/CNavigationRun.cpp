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
#include <optional>
#include <random>
#include <sstream>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
namespace fs = std::filesystem;

namespace risknav::nav {
namespace {
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

/** One run's navigator, outputs and loop state: run()'s locals, shared by
 * its parts, on the closed loop (each cycle: sense, localize, record,
 * navigationStep(); then nav_period in sim_dt sub-steps). Members are
 * destroyed in the reverse order of their declaration, as run()'s locals
 * were: the progress line and the simulated clock first. */
struct CNavigationRun::TRun : public sim::CClosedLoop {
    TRun(CNavigationRun& navRun, const sim::CClosedLoop::TOptions& loopOptions,
         const TNavRunSetup& runSetup)
        : sim::CClosedLoop(navRun.world, loopOptions),
          owner(navRun),
          setup(runSetup),
          robotIf(navRun.world),
          navlog(!runSetup.navlogDir.empty()),
          nav(robotIf, false, false, navlogFolder(runSetup)),
          fixRng(runSetup.seed ^ 0x5EED5EEDull) {}
    TRun(const TRun&) = delete;
    TRun& operator=(const TRun&) = delete;

    /** The navlog folder, created if there is to be a navlog ("." if not). */
    static std::string navlogFolder(const TNavRunSetup& setup) {
        if (setup.navlogDir.empty())
            return ".";
        fs::create_directories(setup.navlogDir);
        return setup.navlogDir;
    }

    bool onCycle(int cycle) override { return owner.runCycle(*this, cycle); }
    void onCycleSteps(int) override { owner.startSteps(*this); }
    void onStepped(int, int, const TPose2D& now) override {
        r.track.emplace_back(now.x, now.y);
    }
    void onCycleEnd(int) override { owner.endSteps(*this); }

    CNavigationRun& owner;
    const TNavRunSetup& setup;
    TNavRunResult r;
    sim::CSimRobotInterface robotIf;
    const bool navlog;
    CRiskAwareReactiveNav nav;
    // the last error's text, for its mrpt_error event (when and where)
    std::string lastMrptError;
    int mrptErrorsSeen = 0;
    // MRPT's navlog writer failing (a full disk) is not a value of the
    // config: the system's reason, as the failed write left it
    int navlogWriteErrno = 0;
    std::string cacheDir;  // this run's subfolder of the PTG cache
    mrpt::nav::TWaypointSequence wps;
    double goalAllowed = 0;  // the end's own allowed distance
    std::unique_ptr<sim::CRawlogWriter> rawlog;
    std::ofstream gt;
    mrpt::poses::CPose2D odoFix;  // believed = odoFix (+) odometry (odometry mode)
    std::mt19937_64 fixRng;
    TPose2D lastOdo, believed;
    size_t eventsSeen = 0;
    // where and when the robot last moved stall_distance away (stall_timeout)
    mrpt::math::TPoint2D stallSpot;
    double stallSince = 0;
    bool everyCycleFailed = true;
    size_t plansSeen = 0;  // the planner's (re)plans already taken in
    std::optional<TSimClock> clock;
    std::optional<CProgress> progress;
};

TNavRunResult CNavigationRun::run(const TNavRunSetup& setup) {
    const auto wall0 = std::chrono::steady_clock::now();
    if (!m_cfg)
        throw std::logic_error("CNavigationRun::run() before loadFromConfigFile()");
    applyRunSetup(setup);
    world.reset(options.start, setup.seed, options.start_time);
    sim::CClosedLoop::TOptions lo;
    lo.sim_dt = options.sim_dt;
    lo.steps_per_cycle = int(std::lround(options.nav_period / options.sim_dt));
    lo.duration_max = options.duration_max;
    // People entering the stopping corridor: the robot cannot stop before
    // them (Choi et al. (002) eqs. 1-5, no beta margin).
    lo.watch_corridor = true;
    TRun s(*this, lo, setup);
    s.robotIf.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    startNavigator(s);
    aimWaypoints(s);
    openRunOutputs(s);

    s.nav.navigateWaypoints(s.wps);
    s.clock.emplace(options.start_time);
    s.progress.emplace(setup.label.empty() ? "navigate" : setup.label,
                       size_t(options.duration_max), "s", setup.quiet);
    s.r.track.emplace_back(world.truePose().x, world.truePose().y);
    s.stallSpot = mrpt::math::TPoint2D(world.truePose().x, world.truePose().y);
    s.stallSince = world.time();
    if (s.run() == sim::CClosedLoop::TEnd::Timeout) {
        s.r.status = "timeout";
        s.nav.cancel();
    }
    s.r.safety = s.safety;
    s.progress->finish();
    finishRun(s);
    s.r.wallSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    return std::move(s.r);
}

void CNavigationRun::applyRunSetup(const TNavRunSetup& setup) {
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
}

void CNavigationRun::startNavigator(TRun& s) {
    CIniConfig& c = *m_cfg;
    const TNavRunSetup& setup = s.setup;
    auto& nav = s.nav;
    nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    // MRPT's errors (e.g. exceptions it catches inside navigationStep()) are
    // counted for summary.json instead of flooding the terminal.
    nav.logging_enable_console_output = false;
    nav.logRegisterCallback([&r = s.r, &lastMrptError = s.lastMrptError,
                             &navlogWriteErrno = s.navlogWriteErrno](
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
    s.cacheDir =
        (fs::path(ptgCacheDir()) / ptgSetName(m_navigatorConfig, shape[0].x)).string();
    const std::string& cacheDir = s.cacheDir;
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
    if (s.navlog) {
        nav.setLogFileDirectory(setup.navlogDir);
        nav.enableLogFile(true);
        nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    }
}

void CNavigationRun::aimWaypoints(TRun& s) const {
    auto& wps = s.wps;
    wps = lapWaypoints(s.setup.laps.value_or(options.laps));
    // the end is aimed at within arrival_radius, judged against its own
    // allowed distance (see TNavigateOptions::arrival_radius)
    const double goalAllowed =
        wps.waypoints.empty() ? 0.0 : wps.waypoints.back().allowed_distance;
    s.goalAllowed = goalAllowed;
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
    s.r.waypointCount = int(wps.waypoints.size());
}

const TWaypointTag* CNavigationRun::tagOf(int i) const {
    const size_t lapLen = waypoints.waypoints.size();
    if (i < 0 || lapLen == 0 || options.mode != "once")
        return nullptr;  // tags of laps beyond the first: the route's order
    const auto it = tags.find(size_t(i));
    return it == tags.end() ? nullptr : &it->second;
}

// The odoFix that makes the belief `pose` now: believed = odoFix (+) odo
// must equal it, so odoFix = pose (+) (-odo). (MRPT's binary "pose - odo"
// is the inverse composition (-odo) (+) pose, the pose seen from the
// odometry frame: composed on the left it would rotate the whole
// odometry track about the world origin by the heading correction, a
// jump of |odo| * dtheta.)
mrpt::poses::CPose2D CNavigationRun::odoFixFor(const TPose2D& pose) const {
    return mrpt::poses::CPose2D(pose) + (-mrpt::poses::CPose2D(world.odometricPose()));
}

void CNavigationRun::openRunOutputs(TRun& s) {
    const TNavRunSetup& setup = s.setup;
    if (!setup.rawlogPath.empty())
        s.rawlog = std::make_unique<sim::CRawlogWriter>(setup.rawlogPath);
    if (!setup.groundtruthPath.empty()) {
        s.gt.open(setup.groundtruthPath);
        s.gt << "% t x y phi  (ground truth at each rawlog frame; t = UNIX time [s], phi "
                "[rad])\n";
    }
    if (options.localization == "mcl") {
        mcl.options.initPose = options.start;
        mcl.initialize(world.grid(), setup.seed);
    }
    const auto& ss = options.start_sigma;
    if (options.localization == "odometry" && (ss[0] > 0 || ss[1] > 0 || ss[2] > 0)) {
        // The belief starts off by an error drawn with start_sigma (the
        // risk evaluator's init_sigma_*), its own generator so that the
        // sensing fixes draw the same numbers with or without it.
        std::mt19937_64 startRng(setup.seed ^ 0x57A27E22ull);
        std::normal_distribution<double> n(0, 1);
        const double ex = ss[0] * n(startRng), ey = ss[1] * n(startRng),
                     ephi = ss[2] * n(startRng);
        s.odoFix = odoFixFor(TPose2D(options.start.x + ex, options.start.y + ey,
                                     options.start.phi + ephi));
    }
    s.lastOdo = world.odometricPose();
    s.believed = options.start;
}

bool CNavigationRun::runCycle(TRun& s, int cycle) {
    const double t = world.time();
    const TPose2D truth = senseAndLocalize(s, t);
    const TNavCycle& rec = stepNavigator(s, cycle, t, truth);
    takeNavEvents(s, truth, rec.poseError);
    if (s.navlogWriteErrno && s.navlog)
        throw writeFailure(s.setup.navlogDir + "/navigation.reactivenavlog",
                           s.navlogWriteErrno);
    checkEngineFailures(s, cycle, t, truth);
    // (the loop ends the run at duration_max: status "timeout")
    return !runEnds(s, cycle, t, truth);
}

TPose2D CNavigationRun::senseAndLocalize(TRun& s, double t) {
    auto& r = s.r;
    auto& believed = s.believed;
    const auto& scans = s.robotIf.senseNow();
    const TPose2D truth = world.truePose(), odo = world.odometricPose();
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CActionRobotMovement2D mv;
    mv.timestamp = world.timestamp();
    mv.computeFromOdometry(mrpt::poses::CPose2D(odo) - mrpt::poses::CPose2D(s.lastOdo),
                           mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    acts.insert(mv);
    mrpt::obs::CSensoryFrame sf;
    sf.insert(scans.laser);
    if (scans.range2)
        sf.insert(scans.range2);
    s.lastOdo = odo;
    if (options.localization == "mcl") {
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
                                            world.truePose().x, world.truePose().y, b});
            mcl.recover();
        }
    } else if (options.localization == "odometry")
        believed = (s.odoFix + mrpt::poses::CPose2D(odo)).asTPose();
    else
        believed = truth;
    s.robotIf.setLocalization(options.localization == "ground_truth"
                                  ? std::nullopt
                                  : std::optional<TPose2D>(believed));
    if (s.rawlog) {
        s.rawlog->write(acts, sf);
        r.rawlogFrames = s.rawlog->frames();
    }
    if (s.gt) {
        char b[128];
        std::snprintf(b, sizeof(b), "%.3f %.6f %.6f %.6f\n", options.start_time + t,
                      truth.x, truth.y, truth.phi);
        s.gt << b;
    }
    return truth;
}

const TNavCycle& CNavigationRun::stepNavigator(TRun& s, int cycle, double t,
                                               const TPose2D& truth) {
    auto& r = s.r;
    auto& nav = s.nav;
    const auto& wps = s.wps;
    const TPose2D& believed = s.believed;
    const auto s0 = std::chrono::steady_clock::now();
    nav.navigationStep();
    const double stepS =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - s0).count();
    r.navStepSeconds += stepS;
    if (m_planner && m_planner->replans().size() > s.plansSeen) {
        s.plansSeen = m_planner->replans().size();
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
    return r.cycles.back();
}

// The navigator's events of this step, and what tagged waypoints do.
void CNavigationRun::takeNavEvents(TRun& s, const TPose2D& truth, double poseError) {
    auto& r = s.r;
    const auto& ev = s.robotIf.navEvents();
    for (; s.eventsSeen < ev.size(); s.eventsSeen++) {
        const auto& e = ev[s.eventsSeen];
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
            const TPose2D fix(truth.x + tag->sigmaX * n(s.fixRng),
                              truth.y + tag->sigmaY * n(s.fixRng),
                              truth.phi + tag->sigmaPhi * n(s.fixRng));
            s.odoFix = odoFixFor(fix);
            char b[120];
            std::snprintf(b, sizeof(b), "%s: pose fixed (error before %.3f m)",
                          tag->detail.c_str(), poseError);
            te.detail = b;
        }
        r.events.push_back(te);
    }
}

void CNavigationRun::checkEngineFailures(TRun& s, int cycle, double t,
                                         const TPose2D& truth) const {
    auto& r = s.r;
    const double t0 = options.start_time;
    // MRPT failing on each of the run's first cycles (exceptions it
    // catches inside navigationStep(), e.g. its asserts on a PTG's
    // clearance_num_points, a v_max_mps of 1e-9 or a score formula
    // whose variable its PTG never sets: the robot never moved, exit 0)
    // is a value of its config that MRPT takes without a check
    const bool failedNow = r.mrptErrors > s.mrptErrorsSeen;
    s.everyCycleFailed = s.everyCycleFailed && failedNow;
    if (s.everyCycleFailed && cycle + 1 == kFailedCyclesForBadConfig) {
        // A config error fails so anywhere; a start MRPT's PTGs find no
        // motion from (beside a wall, the target off to the side) is
        // the run's outcome, not the config's: told in summary.json
        const std::string open = engineFailsInOpenSpace(s.cacheDir, world.time() + t0);
        s.clock->set(t0 + world.time());
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
            t, "mrpt_error", s.nav.getWaypointNavStatus().waypoint_index_current_goal,
            truth.x, truth.y,
            std::to_string(r.mrptErrors - s.mrptErrorsSeen) + " x " + s.lastMrptError});
        s.mrptErrorsSeen = r.mrptErrors;
    }
}

bool CNavigationRun::runEnds(TRun& s, int cycle, double t, const TPose2D& truth) const {
    auto& r = s.r;
    auto& nav = s.nav;
    const TPose2D& believed = s.believed;
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
        return true;
    }
    if (st == mrpt::nav::CAbstractNavigator::IDLE && cycle > 0 && !nav.requestPending()) {
        r.status =
            nav.getWaypointNavStatus().final_goal_reached ? "goal_reached" : "stopped";
        return true;
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
    if (std::hypot(truth.x - s.stallSpot.x, truth.y - s.stallSpot.y) >
            options.stall_distance ||
        targetUnder()) {
        s.stallSpot = mrpt::math::TPoint2D(truth.x, truth.y);
        s.stallSince = t;
    } else if (options.stall_timeout > 0 && t - s.stallSince >= options.stall_timeout) {
        char b[200];
        std::snprintf(b, sizeof(b),
                      "stalled: within %.2f m of (%.2f, %.2f) for %.0f s "
                      "(stall_timeout; MRPT's own alarm did not fire)",
                      options.stall_distance, s.stallSpot.x, s.stallSpot.y,
                      t - s.stallSince);
        r.status = "stalled";
        r.navError = b;
        nav.cancel();
        return true;
    }
    return false;
}

void CNavigationRun::startSteps(TRun& s) {
    auto& r = s.r;
    const std::string& limiter = r.cycles.back().limiter;
    r.timePerLimiter[limiter.empty() ? "none" : limiter] += options.nav_period;
    for (const auto& d : world.agents.discs())
        r.people[d.objectId].emplace_back(d.x, d.y);
}

void CNavigationRun::endSteps(TRun& s) {
    s.r.distance = s.travelled();
    s.clock->set(options.start_time + world.time());
    s.progress->update(size_t(world.time()));
}

void CNavigationRun::finishRun(TRun& s) {
    auto& r = s.r;
    auto& nav = s.nav;
    const auto& wps = s.wps;
    const double t0 = options.start_time;
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
                from += s.options.steps_per_cycle;
        for (size_t k = std::min(from, r.track.size()); k < r.track.size(); k++)
            r.goalTrueDistance = std::min(
                r.goalTrueDistance, std::hypot(r.track[k].x - g.x, r.track[k].y - g.y));
    }
    if (r.status == "goal_reached" && !(r.goalTrueDistance <= s.goalAllowed + 0.03)) {
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
    if (s.rawlog)
        s.rawlog->close();
    if (s.gt.is_open()) {
        s.gt.close();
        if (!s.gt)
            throw std::runtime_error("cannot write " + s.setup.groundtruthPath);
    }
    if (s.navlog) {
        nav.enableLogFile(false);  // closes MRPT's file
        for (const auto& e : fs::directory_iterator(s.setup.navlogDir))
            if (e.path().extension() == ".reactivenavlog")
                r.navlogFile = e.path().string();
    }
}

}  // namespace risknav::nav
