// CAdaptiveSpeedLimiter: the adaptive speed control of Miura et al. 2006 (M1)
// as a speed limiter inside MRPT's reactive engine (CRiskAwareReactiveNav).
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/config_read.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/sim/CSafetyMonitor.h>
#include <risknav/sim/CSimRobotInterface.h>
#include <risknav/sim/CSimWorld.h>
#include <risknav/speed/speed_rules.h>
#include <test_support.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/CPolygon.h>
#include <mrpt/system/filesystem.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

using namespace risknav;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;

namespace {
// ---------------------------------------------------------------------------
// Synthetic worlds, built in code: a risknav world (for its laser and RANGE2
// simulation) on a map drawn here; the robot stands still and the limiter is
// called once per 0.2 s cycle with the scans of that instant.

/** Free cells in [x0, x1] x [y0, y1], walls drawn with wall(). */
mrpt::maps::COccupancyGridMap2D freeMap(double x0, double x1, double y0, double y1) {
    mrpt::maps::COccupancyGridMap2D g(x0, x1, y0, y1, 0.05f);
    g.fill(1.0f);
    return g;
}
void wall(mrpt::maps::COccupancyGridMap2D& g, double x0, double y0, double x1,
          double y1) {
    for (double y = y0; y <= y1 + 1e-9; y += 0.025)
        for (double x = x0; x <= x1 + 1e-9; x += 0.025)
            g.setPos(x, y, 0.0f);
}

/** A world on `g` with a 360 deg laser (8 m) and a 360 deg second range
 * sensor of `range2Max` m, both at the robot's centre, every cycle (a robot
 * standing still sees all around it; a 180 deg laser ahead of the centre
 * would leave the cells beside the robot unobserved, which stops it until it
 * has moved: see the creep test). */
sim::CSimWorld syntheticWorld(const mrpt::maps::COccupancyGridMap2D& g,
                              double range2Max) {
    sim::CSimWorld w;
    w.laser.options.max_range = 8.0;
    w.laser.options.fov_deg = 360;
    w.laser.options.beams = 360;
    w.laser.options.x = 0;
    w.range2.options.enabled = true;
    w.range2.options.label = "RANGE2";
    w.range2.options.fov_deg = 360;
    w.range2.options.beams = 144;
    w.range2.options.max_range = range2Max;
    w.range2.options.noise_std = 0.01;
    w.range2.options.x = 0;
    w.range2.options.z = 0.5;
    w.setMap(g);
    return w;
}

nav::CAdaptiveSpeedLimiter& asAdaptive(const common::CSpeedLimiter::Ptr& p) {
    auto* l = dynamic_cast<nav::CAdaptiveSpeedLimiter*>(p.get());
    if (!l)
        throw std::runtime_error("not a CAdaptiveSpeedLimiter");
    return *l;
}

/** A limiter made by name, MRPT style, from `section` text. */
common::CSpeedLimiter::Ptr makeLimiter(const std::string& text) {
    nav::registerAllClasses_nav();
    auto l = common::CSpeedLimiter::Factory("CAdaptiveSpeedLimiter");
    mrpt::config::CConfigFileMemory c(text);
    l->loadConfig(c, "CAdaptiveSpeedLimiter");
    return l;
}

/** The limits of `cycles` calls, the robot still at `pose`, target `goal`. */
/** A limiter's input at the robot's pose: both scans, sensing k's time. */
common::TSpeedLimitInput sensingInput(const common::TRobotOptions& robot,
                                      const TPose2D& pose,
                                      const sim::CSimWorld::TScans& scans,
                                      const TPoint2D& target, int k,
                                      double desired = 1.1) {
    common::TSpeedLimitInput in;
    in.robot = &robot;
    in.pose = pose;
    in.desiredSpeed = desired;
    in.scan = scans.laser.get();
    in.scan2 = scans.range2.get();
    in.target = target;
    in.time = 100.0 + 0.2 * k;
    return in;
}

std::vector<common::TSpeedLimit> standAndLook(const common::CSpeedLimiter::Ptr& l,
                                              sim::CSimWorld& w, const TPose2D& pose,
                                              const TPoint2D& goal, int cycles,
                                              double desired = 1.1) {
    w.reset(pose, 3);
    common::TRobotOptions robot;  // radius 0.25
    std::vector<common::TSpeedLimit> out;
    for (int k = 0; k < cycles; k++) {
        const auto scans = w.sense();
        out.push_back(l->limit(sensingInput(robot, pose, scans, goal, k, desired)));
        w.step(0, 0, 0.2);
    }
    return out;
}

/** A 2 m wide corridor along x, 20 m long; the robot at x = 2 facing +x. */
mrpt::maps::COccupancyGridMap2D corridor() {
    auto g = freeMap(-1, 21, -3, 3);
    wall(g, -1, -1.2, 21, -1.0);
    wall(g, -1, 1.0, 21, 1.2);
    wall(g, -1, -1.2, -0.8, 1.2);
    wall(g, 20.8, -1.2, 21, 1.2);
    return g;
}
}  // namespace

TEST(AdaptiveLimiter,
     AnUndecidedRegionAheadLimitsTheSpeedAndTheLimitGrowsAsTheMapConfirmsFreeSpace) {
    // RANGE2 (the stereo-like model: N = 5) sees 1.5 m: the fused map is free
    // only there, the corridor beyond is undecided; the target lies 13 m on.
    // A cycle on every call (cycle_decimation = 1): the paper's one cycle per
    // sensing; the default (every 2nd) is the test after this one.
    auto w = syntheticWorld(corridor(), 1.5);
    auto l = makeLimiter("[CAdaptiveSpeedLimiter]\ncycle_decimation = 1\n");
    auto& a = asAdaptive(l);
    EXPECT_EQ(a.necessaryObservations(), 5);
    const auto lim = standAndLook(l, w, TPose2D(2, 0, 0), TPoint2D(15, 0), 12);
    // first cycle: one observation, nothing decided ahead: stop
    EXPECT_EQ(lim.front().maxSpeed, 0.0);
    // once RANGE2's cells are confirmed free (N = 5 observations), faster
    EXPECT_GT(lim.back().maxSpeed, lim.front().maxSpeed);
    for (size_t k = 1; k < lim.size(); k++)
        EXPECT_GE(lim[k].maxSpeed, lim[k - 1].maxSpeed) << k;
    // the measured cycle: the 0.2 s between calls
    EXPECT_NEAR(a.lastCycleTime(), 0.2, 1e-9);
    ASSERT_TRUE(a.lastDecision());
    const auto& d = *a.lastDecision();
    EXPECT_TRUE(d.temporaryTarget);
    EXPECT_EQ(d.reason, speed::TSpeedReason::Undecided);
    // the free space ends ~1.5 m ahead: 1.1 m/s would need d >= 5 x 1.1 x 0.2
    // = 1.1 m to the unknown (its margin disc's front), 0.7 m/s 0.7 m
    EXPECT_DOUBLE_EQ(lim.back().maxSpeed, 0.7);
    EXPECT_NE(lim.back().reason.find("undecided region"), std::string::npos)
        << lim.back().reason;
    EXPECT_NE(lim.back().reason.find("m ahead"), std::string::npos);
    // the rule d / (v T) >= N, on the fastest speed's own d
    EXPECT_LT(d.dUndecided / (1.1 * 0.2), 5.0);
    // a longer cycle T (configured, not measured) asks for more distance
    // per observation: a lower limit on the same map. A constant in place of
    // d / (v T) >= N would not see T.
    auto slow = makeLimiter(
        "[CAdaptiveSpeedLimiter]\nmeasure_cycle_time = false\ncycle_time = 0.4\n"
        "cycle_decimation = 1\n");
    const auto limSlow = standAndLook(slow, w, TPose2D(2, 0, 0), TPoint2D(15, 0), 12);
    EXPECT_NEAR(asAdaptive(slow).lastCycleTime(), 0.4, 1e-12);
    EXPECT_LT(limSlow.back().maxSpeed, lim.back().maxSpeed);
    EXPECT_DOUBLE_EQ(limSlow.back().maxSpeed, 0.35);
    // and a sensor that needs more observations (N = 9) too
    auto weak = makeLimiter(
        "[CAdaptiveSpeedLimiter]\nrange2_model = Weak\ncycle_decimation = 1\n"
        "[Weak]\np_obs_given_obstacle = 0.55\np_obs_given_free = 0.45\n");
    EXPECT_GT(asAdaptive(weak).necessaryObservations(), 5);
    const auto limWeak = standAndLook(weak, w, TPose2D(2, 0, 0), TPoint2D(15, 0), 16);
    EXPECT_LT(limWeak.back().maxSpeed, lim.back().maxSpeed);
    // a desired speed below the limit is not limited: empty reason
    const auto calm =
        standAndLook(makeLimiter("[CAdaptiveSpeedLimiter]\ncycle_decimation = 1\n"), w,
                     TPose2D(2, 0, 0), TPoint2D(15, 0), 12, 0.3);
    EXPECT_DOUBLE_EQ(calm.back().maxSpeed, 0.3);
    EXPECT_EQ(calm.back().reason, "");
}

TEST(AdaptiveLimiter,
     ACycleOnEveryOtherSensingMeasuresTwiceTheCycleAndActsOneCycleLater) {
    // A cycle on every other sensing (cycle_decimation = 2) against a limiter with a
    // cycle on every call that is given only every other sensing: the same
    // cycles (the same scans, T = 0.4 s measured), each decision taken one
    // cycle later (when the next cycle starts) and held for two calls; the
    // first cycle is waited for.
    auto w = syntheticWorld(corridor(), 1.5);
    const auto every2nd =
        standAndLook(makeLimiter("[CAdaptiveSpeedLimiter]\ncycle_decimation = 2\n"), w,
                     TPose2D(2, 0, 0), TPoint2D(15, 0), 24);
    auto each = makeLimiter("[CAdaptiveSpeedLimiter]\ncycle_decimation = 1\n");
    w.reset(TPose2D(2, 0, 0), 3);
    common::TRobotOptions robot;
    std::vector<common::TSpeedLimit> reference;
    for (int k = 0; k < 24; k++) {
        const auto scans = w.sense();
        if (k % 2 == 0) {
            common::TSpeedLimitInput in;
            in.robot = &robot;
            in.pose = TPose2D(2, 0, 0);
            in.desiredSpeed = 1.1;
            in.scan = scans.laser.get();
            in.scan2 = scans.range2.get();
            in.target = TPoint2D(15, 0);
            in.time = 100.0 + 0.2 * k;
            reference.push_back(each->limit(in));
        }
        w.step(0, 0, 0.2);
    }
    EXPECT_NEAR(asAdaptive(each).lastCycleTime(), 0.4, 1e-9);
    std::set<double> seen;
    for (size_t s = 0; s < every2nd.size(); s++) {
        const size_t cycle = s < 2 ? 0 : (s - 2) / 2;
        EXPECT_EQ(every2nd[s].maxSpeed, reference[cycle].maxSpeed) << s;
        EXPECT_EQ(every2nd[s].reason, reference[cycle].reason) << s;
        seen.insert(every2nd[s].maxSpeed);
    }
    // the limit changed over the run (from 0 up), so a decision taken at once
    // (one call earlier) would have failed the comparison above
    EXPECT_GE(seen.size(), 2u);
    // T = 0.4 s: the limit of a configured T = 0.4 s at one cycle a call
    // (0.35 m/s, the first test)
    EXPECT_DOUBLE_EQ(every2nd.back().maxSpeed, 0.35);
}

TEST(AdaptiveLimiter, ADecimatedSecondSensorIsKeptUntilACycleTakesIt) {
    // RANGE2 on every other sensing, on the sensings between the limiter's
    // cycles: each cycle takes the one before (at the pose it was taken
    // from). A limiter that dropped it would never see free space confirmed
    // by both sensors (held at 0, then creeping at 0.2 m/s).
    auto w = syntheticWorld(corridor(), 1.5);
    w.range2.options.frame_decimation = 2;
    auto l = makeLimiter("[CAdaptiveSpeedLimiter]\ncycle_decimation = 2\n");
    const TPose2D pose(2, 0, 0);
    w.reset(pose, 3);
    (void)w.sense();  // RANGE2 now on the limiter's odd sensings
    common::TRobotOptions robot;
    common::TSpeedLimit last;
    int withRange2 = 0;
    for (int k = 0; k < 24; k++) {
        const auto scans = w.sense();
        const auto in = sensingInput(robot, pose, scans, TPoint2D(15, 0), k);
        withRange2 += (k % 2 == 1 && in.scan2) ? 1 : 0;
        EXPECT_EQ(in.scan2 != nullptr, k % 2 == 1) << k;
        last = l->limit(in);
        w.step(0, 0, 0.2);
    }
    EXPECT_EQ(withRange2, 12);
    EXPECT_DOUBLE_EQ(last.maxSpeed, 0.35);
    EXPECT_EQ(last.reason.find("creeping"), std::string::npos) << last.reason;
    EXPECT_NEAR(asAdaptive(l).lastCycleTime(), 0.4, 1e-9);
}

TEST(AdaptiveLimiter, WithRange2SeeingFarTheCorridorIsFastAndWithoutAnyScanItCreeps) {
    // RANGE2 sees 5 m: the unknown is far enough for the fastest speed
    auto w = syntheticWorld(corridor(), 5.0);
    auto l = makeLimiter("[CAdaptiveSpeedLimiter]\n");
    const auto lim = standAndLook(l, w, TPose2D(2, 0, 0), TPoint2D(15, 0), 12);
    EXPECT_DOUBLE_EQ(lim.back().maxSpeed, 1.1);
    EXPECT_EQ(lim.back().reason, "");
    // no scans at all: nothing is ever decided; held N = 5 cycles at 0, the
    // limiter lets the engine creep on at the slowest speed
    auto blind = makeLimiter("[CAdaptiveSpeedLimiter]\ncycle_decimation = 1\n");
    common::TRobotOptions robot;
    for (int k = 0; k < 6; k++) {
        common::TSpeedLimitInput in;
        in.robot = &robot;
        in.pose = TPose2D(2, 0, 0);
        in.desiredSpeed = 1.0;
        in.target = TPoint2D(15, 0);
        in.time = 0.2 * k;
        const auto r = blind->limit(in);
        if (k < 4) {
            EXPECT_EQ(r.maxSpeed, 0.0) << k;
        } else {
            EXPECT_DOUBLE_EQ(r.maxSpeed, 0.2) << k;
            EXPECT_NE(r.reason.find("creeping"), std::string::npos) << r.reason;
        }
    }
}

TEST(AdaptiveLimiter, ANarrowGapLimitsToTheGapRulesSpeed) {
    // A wall across the room at x in [0, 0.1] with a 0.9 m gap (0.8 m once
    // the sensed walls have grown by the range uncertainty): with the
    // radius 0.25 m, the inflations are 0.55 / 0.45 / 0.35 / 0.30 m, and only
    // 0.35 and 0.2 m/s fit through the 0.4 m half-gap; the wall spans the room
    // (no detour). Just before the gap (section 4.2: the faster margins fail
    // within their next two cycles), the gap rule's speed is 0.35 m/s.
    auto g = freeMap(-4, 4, -3, 3);
    wall(g, 0.0, -3, 0.1, -0.45);
    wall(g, 0.0, 0.45, 0.1, 3);
    auto w = syntheticWorld(g, 5.0);
    auto l = makeLimiter("[CAdaptiveSpeedLimiter]\n");
    const auto lim = standAndLook(l, w, TPose2D(-0.4, 0, 0), TPoint2D(2.0, 0), 15);
    const auto& d = *asAdaptive(l).lastDecision();
    EXPECT_FALSE(d.temporaryTarget);
    EXPECT_EQ(d.safeByGap, (std::vector<size_t>{2, 3}));
    EXPECT_FALSE(d.perSpeed[0].reached);
    EXPECT_EQ(d.reason, speed::TSpeedReason::Narrow);
    EXPECT_DOUBLE_EQ(lim.back().maxSpeed, 0.35);
    EXPECT_NE(lim.back().reason.find("narrow passage"), std::string::npos)
        << lim.back().reason;
    // the same gap 2 m wide: no narrow passage, the fastest speed
    auto wide = freeMap(-4, 4, -3, 3);
    wall(wide, 0.0, -3, 0.1, -1.0);
    wall(wide, 0.0, 1.0, 0.1, 3);
    auto w2 = syntheticWorld(wide, 5.0);
    auto l2 = makeLimiter("[CAdaptiveSpeedLimiter]\n");
    const auto lim2 = standAndLook(l2, w2, TPose2D(-0.4, 0, 0), TPoint2D(2.0, 0), 15);
    EXPECT_EQ(asAdaptive(l2).lastDecision()->safeByGap.size(), 4u);
    EXPECT_DOUBLE_EQ(lim2.back().maxSpeed, 1.1);
}

TEST(AdaptiveLimiter, ItsGuidePointLiesAheadOnItsPlannedWayRoundAWall) {
    // A wall between the robot and its target, open at its north end: the
    // planned way goes north round it, and the guide point is on that way,
    // lookahead ahead, north of the straight line to the target.
    auto g = freeMap(-4, 4, -3, 3);
    wall(g, 0.0, -3, 0.1, 1.5);
    auto w = syntheticWorld(g, 5.0);
    auto l = makeLimiter("[CAdaptiveSpeedLimiter]\n");
    const TPose2D pose(-1.0, 0, 0);
    EXPECT_FALSE(l->guidePoint(pose, 1.5));  // nothing planned yet
    standAndLook(l, w, pose, TPoint2D(1.5, 0), 15);
    const auto& d = *asAdaptive(l).lastDecision();
    ASSERT_NE(d.reason, speed::TSpeedReason::Unreachable);
    const auto gp = l->guidePoint(pose, 1.5);
    ASSERT_TRUE(gp);
    EXPECT_NEAR(std::hypot(gp->x - pose.x, gp->y - pose.y), 1.5, 0.1);
    EXPECT_GT(gp->y, 0.5) << gp->x << " " << gp->y;  // round the wall's north end
    EXPECT_LT(gp->x, 0.0);                           // not through the wall
    // the stopping-distance limiter plans no way: no guide point
    auto stop = common::CSpeedLimiter::Factory("CStoppingDistanceLimiter");
    EXPECT_FALSE(stop->guidePoint(pose, 1.5));
}

TEST(AdaptiveLimiter, AnObservedCycleIsTheCycleLimitWouldRunOnWorkerOrCallerThread) {
    // Three limiters on the same scans: one only called (limit() runs each
    // cycle), one observed on its worker thread, one observed on the
    // caller's thread (observe() runs the cycle, limit() takes it). Some
    // cycles are observed without a limit() (the engine commanded no
    // forward speed): they still map.
    auto w = syntheticWorld(corridor(), 1.5);
    const TPose2D pose(2.0, 0.0, 0.0);
    const TPoint2D goal(15.0, 0.0);
    auto called = makeLimiter("[CAdaptiveSpeedLimiter]\n");
    auto worker = makeLimiter("[CAdaptiveSpeedLimiter]\nworker_thread = true\n");
    auto caller = makeLimiter("[CAdaptiveSpeedLimiter]\nworker_thread = false\n");
    auto observedOnly = makeLimiter("[CAdaptiveSpeedLimiter]\n");
    w.reset(pose, 3);
    common::TRobotOptions robot;
    for (int k = 0; k < 8; k++) {
        const auto scans = w.sense();
        common::TSpeedLimitInput in;
        in.robot = &robot;
        in.pose = pose;
        in.scan = scans.laser.get();
        in.scan2 = scans.range2.get();
        in.target = goal;
        in.time = 100.0 + 0.2 * k;
        worker->observe(in);
        caller->observe(in);
        observedOnly->observe(in);
        in.desiredSpeed = 1.1;
        if (k == 0 || k == 3 || k == 7) {
            const auto a = called->limit(in), b = worker->limit(in),
                       c = caller->limit(in);
            EXPECT_EQ(b.maxSpeed, c.maxSpeed) << k;
            EXPECT_EQ(b.reason, c.reason) << k;
            if (k == 0) {  // the same cycles so far
                EXPECT_EQ(a.maxSpeed, b.maxSpeed);
                EXPECT_EQ(a.reason, b.reason);
            }
        } else {
            worker->finishObserved();
        }
        w.step(0, 0, 0.2);
    }
    const auto& dw = asAdaptive(worker).lastDecision();
    const auto& dc = asAdaptive(caller).lastDecision();
    ASSERT_TRUE(dw && dc);
    EXPECT_EQ(dw->speed, dc->speed);
    EXPECT_EQ(dw->dUndecided, dc->dUndecided);
    EXPECT_EQ(dw->path.points.size(), dc->path.points.size());
    // the cycles observed without a limit() mapped: more of RANGE2's 1.5 m
    // is known free (N = 5) than after the called limiter's three cycles
    auto freeCells = [](const common::CSpeedLimiter::Ptr& l) {
        const auto& cells = asAdaptive(l).pipeline()->fused().cells;
        return std::count(cells.begin(), cells.end(), mapping::TFusedCell::Free);
    };
    EXPECT_EQ(freeCells(worker), freeCells(caller));
    EXPECT_GT(freeCells(worker), freeCells(called));
    // observed cycles alone (no limit() at all) map the same
    EXPECT_EQ(freeCells(observedOnly), freeCells(worker));
}

TEST(AdaptiveLimiter, BadOrMissingKeysAreClearErrorsNamingSectionAndKey) {
    nav::registerAllClasses_nav();
    struct TCase {
        std::string text, section, key;
    };
    const std::vector<TCase> cases = {
        {"speeds = 1.1 0.7\n", "CAdaptiveSpeedLimiter", "margins"},
        {"speeds = 1.1 fast 0.35 0.2\n", "CAdaptiveSpeedLimiter", "speeds"},
        {"speeds = 0.7 1.1 0.35 0.2\n", "CAdaptiveSpeedLimiter", "speeds"},
        {"cycle_time = -0.3\n", "CAdaptiveSpeedLimiter", "cycle_time"},
        {"gap_threshold = 0\n", "CAdaptiveSpeedLimiter", "gap_threshold"},
        {"free_threshold = 0.8\n", "CAdaptiveSpeedLimiter", "free_threshold"},
        {"measure_cycle_time = sometimes\n", "CAdaptiveSpeedLimiter",
         "measure_cycle_time"},
        {"local_map_size = 1\n", "CAdaptiveSpeedLimiter", "local_map_size"},
        {"memory_size = 5\n", "CAdaptiveSpeedLimiter", "memory_size"},
        {"spedes = 1.1\n", "CAdaptiveSpeedLimiter", "spedes"},
        {"worker_thread = maybe\n", "CAdaptiveSpeedLimiter", "worker_thread"},
        // a model section named but missing
        {"laser_model = MapLaser\n", "CAdaptiveSpeedLimiter", "laser_model"},
        // a model that never decides a cell (no N)
        {"range2_model = MapRange2\n[MapRange2]\np_obs_given_obstacle = 0.4\n"
         "p_obs_given_free = 0.45\n",
         "MapRange2", "p_obs_given_obstacle"},
        {"range2_model = MapRange2\n[MapRange2]\np_obs_given_free = 1.5\n", "MapRange2",
         "p_obs_given_free"},
    };
    for (const auto& c : cases) {
        auto l = common::CSpeedLimiter::Factory("CAdaptiveSpeedLimiter");
        mrpt::config::CConfigFileMemory cfg("[CAdaptiveSpeedLimiter]\n" + c.text);
        try {
            l->loadConfig(cfg, "CAdaptiveSpeedLimiter");
            ADD_FAILURE() << "accepted: " << c.text;
        } catch (const common::CBadInputError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("[" + c.section + "]"), std::string::npos) << m;
            EXPECT_NE(m.find(c.key), std::string::npos) << m;
        }
    }
    // the defaults are valid and read back the same
    auto l = makeLimiter("[CAdaptiveSpeedLimiter]\n");
    mrpt::config::CConfigFileMemory saved;
    l->saveConfig(saved, "CAdaptiveSpeedLimiter");
    auto again = makeLimiter(saved.getContent());
    EXPECT_EQ(asAdaptive(again).options.speed.speeds, asAdaptive(l).options.speed.speeds);
    EXPECT_EQ(asAdaptive(again).options.memory_size, asAdaptive(l).options.memory_size);
}

TEST(AdaptiveLimiter, ANewTargetIsPlannedToAtItsOwnSensingAlsoBetweenCycles) {
    // cycle_decimation = 2, the target changed on a sensing between two
    // cycles (a waypoint reached): that sensing runs a cycle and its decision
    // is the one in use by the end of the step, taken by limit() or, when the
    // engine calls none, by finishObserved(). Kept to the old target's
    // decision (the count's next cycle), the limit and the guide point would
    // lead towards the waypoint already reached.
    for (const bool callsLimit : {true, false}) {
        auto w = syntheticWorld(corridor(), 1.5);
        auto l = makeLimiter("[CAdaptiveSpeedLimiter]\ncycle_decimation = 2\n");
        auto& a = asAdaptive(l);
        const TPose2D pose(2, 0, 0);
        w.reset(pose, 3);
        common::TRobotOptions robot;
        const TPoint2D far(15, 0), near(2.6, 0);  // near: in the free space seen
        for (int k = 0; k < 15; k++) {
            const auto scans = w.sense();
            // sensing 13: not a cycle's by the count
            const auto in = sensingInput(robot, pose, scans, k < 13 ? far : near, k);
            if (k < 13 || callsLimit) {
                (void)l->limit(in);
            } else {
                l->observe(in);
                l->finishObserved();
            }
            ASSERT_TRUE(a.lastDecision()) << k;
            const auto& d = *a.lastDecision();
            if (k < 13) {
                EXPECT_TRUE(d.temporaryTarget) << k;  // far is beyond the map
            } else {
                EXPECT_FALSE(d.temporaryTarget) << k << " limit() " << callsLimit;
                EXPECT_NEAR(d.target.x, near.x, 1e-9) << k << " limit() " << callsLimit;
            }
            w.step(0, 0, 0.2);
        }
    }
}
