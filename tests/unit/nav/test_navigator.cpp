// CRiskAwareReactiveNav: MRPT's reactive engine with risknav's speed limiters
// inside it, driving the office world through CSimRobotInterface.
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/nav/escape_heading.h>
#include <risknav/nav/waypoint_file.h>
#include <risknav/sim/CSimRobotInterface.h>
#include <risknav/sim/CSimWorld.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>
#include <test_support.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/math/CPolygon.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/nav/reactive/CLogFileRecord.h>
#include <mrpt/nav/tpspace/CParameterizedTrajectoryGenerator.h>
#include <mrpt/system/filesystem.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>

using namespace risknav;
using mrpt::math::TPose2D;

namespace {
// MRPT's shipped reactive2d_config.ini plus risknav's sections.
std::string navConfig(const std::string& extra) {
    std::ifstream f(mrpt::system::find_mrpt_shared_dir() +
                    "config_files/navigation-ptgs/reactive2d_config.ini");
    std::stringstream ss;
    ss << f.rdbuf() << "\n" << extra;
    return ss.str();
}

struct TRun {
    bool reached = false;
    int limitedCycles = 0, cycles = 0;
    double maxOverLimit = -1e9;  // max over cycles of |v sent| - limit
    std::string reasonSeen;
    int sensingChecks = 0, sensedOtherScans = 0;  // checkSensing
};

bool sameRanges(const mrpt::obs::CObservation2DRangeScan& a,
                const mrpt::obs::CObservation2DRangeScan& b) {
    if (a.getScanSize() != b.getScanSize())
        return false;
    for (size_t i = 0; i < a.getScanSize(); i++)
        if (a.getScanRange(i) != b.getScanRange(i) ||
            a.getScanRangeValidity(i) != b.getScanRangeValidity(i))
            return false;
    return true;
}

// checkSensing: the first 60 steps only, and whether the scans MRPT sensed in a
// step (sensingChecks) are the first the world gives from the state before
// it (a copy of the world senses once): the world was sensed once a step.
// senseFirst: each step begins with the robot's senseNow(), as
// risknav-navigate's loop does (for its localizer).
TRun driveOffice(const std::string& extra, bool checkSensing = false,
                 bool senseFirst = false) {
    common::CIniConfig cfg(test::sourcePath("datasets/office/world.ini"));
    sim::CSimWorld world;
    world.loadFromConfigFile(cfg);
    world.agents.walkers.clear();
    world.reset(TPose2D(3.0, 3.0, M_PI / 2), 11);
    sim::CSimRobotInterface robotIf(world);
    robotIf.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    nav::CRiskAwareReactiveNav nav(robotIf);
    nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    const_cast<mrpt::system::CTimeLogger&>(nav.getDelaysTimeLogger()).disable();
    mrpt::config::CConfigFileMemory navCfg(navConfig(extra));
    nav.loadConfigFile(navCfg);
    nav.params_abstract_ptg_navigator.ptg_cache_files_directory = test::freshDir("ptg");
    mrpt::math::CPolygon shape;
    for (int i = 0; i < 16; i++)
        shape.AddVertex(world.robot.radius * std::cos(i * M_PI / 8),
                        world.robot.radius * std::sin(i * M_PI / 8));
    nav.changeRobotShape(shape);
    nav.initialize();
    nav.enableKeepLogRecords(true);
    mrpt::nav::TWaypointSequence wps;
    for (const auto& [x, y] :
         std::vector<std::pair<double, double>>{{3.0, 6.6}, {9.0, 6.6}})
        wps.waypoints.emplace_back(x, y, 0.3, false);
    nav.navigateWaypoints(wps);
    mrpt::Clock::setSimulatedTime(mrpt::Clock::fromDouble(1.6e9));
    mrpt::Clock::setActiveClock(mrpt::Clock::Simulated);
    TRun r;
    for (int step = 0; step < 1500; step++) {
        if (checkSensing && step == 60)
            break;
        std::optional<sim::CSimWorld> before;
        if (checkSensing)
            before = world;
        if (senseFirst)
            robotIf.senseNow();
        nav.navigationStep();
        // (a step in which MRPT sensed nothing, e.g. the one that ends the
        // navigation, leaves the last step's scans: not checked)
        const auto& sensed = robotIf.lastScans().laser;
        if (before && sensed && sensed->timestamp == before->timestamp()) {
            r.sensingChecks++;
            if (!sameRanges(*before->sense().laser, *sensed))
                r.sensedOtherScans++;
        }
        const auto st = nav.getCurrentState();
        if (st == mrpt::nav::CAbstractNavigator::IDLE ||
            st == mrpt::nav::CAbstractNavigator::NAV_ERROR)
            break;
        mrpt::nav::CLogFileRecord rec;
        nav.getLastLogRecord(rec);
        if (rec.values.count("speed_limit")) {
            r.cycles++;
            const std::string& why = rec.additional_debug_msgs["speed_limiter"];
            if (why != "none") {
                r.limitedCycles++;
                r.reasonSeen = why;
            }
            // The command MRPT records is the limited one.
            if (rec.cmd_vel && rec.cmd_vel->getVelCmdLength() > 0)
                r.maxOverLimit =
                    std::max(r.maxOverLimit, std::abs(rec.cmd_vel->getVelCmdElement(0)) -
                                                 rec.values["speed_limit"]);
        }
        for (int k = 0; k < 4; k++)
            world.step(0.05);
        mrpt::Clock::setSimulatedTime(mrpt::Clock::fromDouble(1.6e9 + world.time()));
    }
    mrpt::Clock::setActiveClock(mrpt::Clock::Realtime);
    r.reached = nav.getWaypointNavStatus().final_goal_reached;
    return r;
}
}  // namespace

TEST(RiskAwareNav, WithoutLimitersItIsTheBareEngine) {
    const TRun r = driveOffice("");
    EXPECT_TRUE(r.reached);
    EXPECT_GT(r.cycles, 20);
    EXPECT_EQ(r.limitedCycles, 0);
}

TEST(RiskAwareNav, TheStoppingLimiterWinsAndIsRecorded) {
    // A generous stopping margin makes the limiter stop the robot at the
    // door and the corridor walls now and then: the limited command is what
    // MRPT records and sends, and the record names the limiter and why.
    const TRun r = driveOffice(
        "[CRiskAwareReactiveNav]\nspeed_limiters = CStoppingDistanceLimiter\n"
        "[CStoppingDistanceLimiter]\nmargin = 0.5\nlateral_margin = 0.05\n"
        "[Robot]\nradius = 0.25\n");
    EXPECT_GT(r.limitedCycles, 0);
    EXPECT_NE(r.reasonSeen.find("CStoppingDistanceLimiter: obstacle within the stopping"),
              std::string::npos)
        << r.reasonSeen;
    EXPECT_LE(r.maxOverLimit, 1e-9);
}

TEST(RiskAwareNav, TheAdaptiveLimiterObservesTheScansMrptSensesAndTheWorldSensesOnce) {
    // On a risknav world the limiters observe() before MRPT's step senses
    // (CSimRobotInterface::senseAhead()): MRPT must then get those very
    // scans, the world sensed once a step (sensing again would hand MRPT a
    // second noise draw, and the limiter a scan MRPT never saw). After the
    // robot's own senseNow() (risknav-navigate's loop) those scans are the
    // step's (checked: a senseAhead() that always senses fails here).
    for (const auto& [limiters, senseFirst] : std::vector<std::pair<std::string, bool>>{
             {"CAdaptiveSpeedLimiter", false}, {"CAdaptiveSpeedLimiter", true}}) {
        const TRun r = driveOffice(
            "[CRiskAwareReactiveNav]\nspeed_limiters = " + limiters +
                "\n[CAdaptiveSpeedLimiter]\n[Robot]\nradius = 0.25\nmax_v = 1.1\n",
            true, senseFirst);
        EXPECT_GE(r.sensingChecks, 55) << limiters << senseFirst;
        EXPECT_EQ(r.sensedOtherScans, 0) << limiters << senseFirst;
    }
}

TEST(RiskAwareNav, UnknownLimiterIsAClearError) {
    common::CIniConfig cfg(test::sourcePath("datasets/office/world.ini"));
    sim::CSimWorld world;
    world.loadFromConfigFile(cfg);
    sim::CSimRobotInterface robotIf(world);
    nav::CRiskAwareReactiveNav nav(robotIf);
    nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    mrpt::config::CConfigFileMemory navCfg(
        navConfig("[CRiskAwareReactiveNav]\nspeed_limiters = CNoSuchLimiter\n"));
    try {
        nav.loadConfigFile(navCfg);
        ADD_FAILURE() << "accepted";
    } catch (const common::CBadInputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("CNoSuchLimiter"), std::string::npos) << m;
        EXPECT_NE(m.find("CStoppingDistanceLimiter"), std::string::npos) << m;
    }
}

TEST(RiskAwareNav, SaveConfigFileLoadsBackComplete) {
    // What saveConfigFile() writes loads back, into CRiskAwareReactiveNav and
    // into MRPT's bare engine, and saves again to the same text: MRPT's
    // sections (with the PTGs and the robot shape, which MRPT 2.5.8's own
    // writer leaves out) and risknav's. Options set after loading (a shape,
    // a key) survive the trip.
    common::CIniConfig cfg(test::sourcePath("datasets/office/world.ini"));
    sim::CSimWorld world;
    world.loadFromConfigFile(cfg);
    sim::CSimRobotInterface robotIf(world);
    nav::CRiskAwareReactiveNav a(robotIf), b(robotIf);
    a.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    b.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    mrpt::config::CConfigFileMemory in(
        navConfig("[CRiskAwareReactiveNav]\nspeed_limiters = CStoppingDistanceLimiter "
                  "CAdaptiveSpeedLimiter\n[CStoppingDistanceLimiter]\nmargin = 0.35\n"
                  "[CAdaptiveSpeedLimiter]\nspeeds = 0.9 0.4\nmargins = 0.2 0.1\n"
                  "[Robot]\nradius = 0.3\nmax_v = 1.0\n"));
    a.loadConfigFile(in);
    mrpt::math::CPolygon shape;
    for (int i = 0; i < 5; i++)
        shape.AddVertex(0.3 * std::cos(i * 2 * M_PI / 5),
                        0.3 * std::sin(i * 2 * M_PI / 5));
    a.changeRobotShape(shape);
    a.params_abstract_ptg_navigator.robot_absolute_speed_limits.robotMax_V_mps = 0.8;
    mrpt::config::CConfigFileMemory saved;
    a.saveConfigFile(saved);
    std::string text;
    saved.getContent(text);
    // loaded from the text, as from a file
    mrpt::config::CConfigFileMemory again(text);
    ASSERT_NO_THROW(b.loadConfigFile(again));
    mrpt::config::CConfigFileMemory savedAgain;
    b.saveConfigFile(savedAgain);
    std::string text2;
    savedAgain.getContent(text2);
    EXPECT_EQ(text, text2);
    ASSERT_EQ(b.getPTG_count(), a.getPTG_count());
    ASSERT_GE(a.getPTG_count(), 2u);
    for (size_t i = 0; i < a.getPTG_count(); i++)
        EXPECT_EQ(b.getPTG(i)->getDescription(), a.getPTG(i)->getDescription());
    // the shape set after loading (MRPT holds it in floats), in both texts
    EXPECT_NE(text2.find("RobotModel_shape2D_xs = 0.300000012 0.0927051008"),
              std::string::npos)
        << text2;
    EXPECT_DOUBLE_EQ(
        b.params_abstract_ptg_navigator.robot_absolute_speed_limits.robotMax_V_mps, 0.8);
    ASSERT_EQ(b.limiters().size(), 2u);
    const auto* l =
        dynamic_cast<const sim::CStoppingDistanceLimiter*>(b.limiters()[0].get());
    ASSERT_TRUE(l);
    EXPECT_DOUBLE_EQ(l->options.margin, 0.35);
    const auto* ad =
        dynamic_cast<const nav::CAdaptiveSpeedLimiter*>(b.limiters()[1].get());
    ASSERT_TRUE(ad);
    EXPECT_EQ(ad->options.speed.speeds, (std::vector<double>{0.9, 0.4}));
    EXPECT_DOUBLE_EQ(b.robot.radius, 0.3);
    EXPECT_EQ(b.riskOptions.speed_limiters, a.riskOptions.speed_limiters);
    // MRPT's bare engine reads the same file
    mrpt::nav::CReactiveNavigationSystem bare(robotIf);
    bare.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    ASSERT_NO_THROW(bare.loadConfigFile(again));
    EXPECT_EQ(bare.getPTG_count(), a.getPTG_count());
}

TEST(AfraidLimiter, SlowsAheadOfAZoneOnlyWhenHeadingIntoIt) {
    // A 10 x 4 m corridor grid, 20 passes along y = 2 and a door at x = 5
    // where obstacles burst out on half of them.
    mrpt::maps::COccupancyGridMap2D map(0, 10, 0, 4, 0.1f);
    afraid::CAfraidGrid g(map);
    for (int pass = 0; pass < 20; pass++) {
        g.addPass(0.5, 2.0);
        g.addTraversal(0.5, 2.0, 9.5, 2.0);
        if (pass % 2 == 0)
            g.addObstacleEvent(5.0, 2.0);
    }
    nav::registerAllClasses_nav();
    auto made = common::CSpeedLimiter::Factory("CAfraidSpeedLimiter");
    auto* l = dynamic_cast<nav::CAfraidSpeedLimiter*>(made.get());
    ASSERT_TRUE(l);
    l->setGrid(g);
    EXPECT_GT(l->levelAt(5.0, 2.0), l->options.zone_threshold);
    EXPECT_LT(l->levelAt(1.0, 2.0), l->options.zone_threshold);
    common::TRobotOptions robot;  // d_stop(0.8) = 1.04 m, radius 0.25
    auto limitAt = [&](double x, double phi) {
        common::TSpeedLimitInput in;
        in.robot = &robot;
        in.pose = TPose2D(x, 2.0, phi);
        in.desiredSpeed = 0.8;
        return made->limit(in);
    };
    EXPECT_DOUBLE_EQ(limitAt(1.0, 0).maxSpeed, 0.8);  // far from the door
    EXPECT_DOUBLE_EQ(limitAt(3.9, 0).maxSpeed, 0.2);  // the door within d_stop ahead
    EXPECT_NE(limitAt(3.9, 0).reason.find("afraid zone"), std::string::npos);
    EXPECT_DOUBLE_EQ(limitAt(3.9, M_PI).maxSpeed, 0.8);  // driving away from it
    EXPECT_DOUBLE_EQ(limitAt(5.0, M_PI).maxSpeed, 0.2);  // inside it
    // MRPT asking for more than v_max far from any zone: capped at v_max, and
    // the reason says so (it once claimed a zone ahead)
    common::TSpeedLimitInput fast;
    fast.robot = &robot;
    fast.pose = TPose2D(1.0, 2.0, 0);
    fast.desiredSpeed = 1.0;
    const auto capped = made->limit(fast);
    EXPECT_DOUBLE_EQ(capped.maxSpeed, 0.8);
    EXPECT_EQ(capped.reason.find("afraid zone"), std::string::npos) << capped.reason;
    EXPECT_NE(capped.reason.find("v_max"), std::string::npos) << capped.reason;
    fast.pose = TPose2D(3.9, 2.0, 0);
    EXPECT_NE(made->limit(fast).reason.find("afraid zone"), std::string::npos);
}

TEST(AfraidLimiter, BadFilesAndKeysAreClearErrors) {
    const std::string d = test::freshDir("afraid");
    test::writeFile(d + "/bad.afraid", "not an afraid file");
    nav::registerAllClasses_nav();
    for (const auto& [text, expect] : std::vector<std::pair<std::string, std::string>>{
             // the file's own error, after the key that named it
             {"[CAfraidSpeedLimiter]\nafraid_file = " + d + "/bad.afraid\n",
              "[CAfraidSpeedLimiter] afraid_file: " + d + "/bad.afraid"},
             {"[CAfraidSpeedLimiter]\nafraid_file = " + d + "\n",
              "is a folder, not a file"},
             {"[CAfraidSpeedLimiter]\nafraid_file = " + d + "/none.afraid\n",
              "none.afraid"},
             {"[CAfraidSpeedLimiter]\n", "afraid_file"}}) {
        mrpt::config::CConfigFileMemory c(text);
        auto l = common::CSpeedLimiter::Factory("CAfraidSpeedLimiter");  // a fresh one
        try {
            l->loadConfig(c, "CAfraidSpeedLimiter");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const common::CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
        }
    }
}

TEST(WaypointFile, SpeedRatioOtherThanOneIsRefusedWithTheReason) {
    // MRPT 2.5.8 applies wpNNN_speed_ratio only within 0.1 m of the waypoint,
    // where it is already reached: accepted, it changed nothing. 1 (MRPT's
    // default, what risknav-viewpoint-plan writes) is taken.
    const std::string d = test::freshDir("wpfile");
    const std::string head =
        "[Waypoints]\nwaypoint_count = 2\nwp000_target_x = 5\nwp000_target_y = 6.6\n"
        "wp000_target_frame_id = map\nwp001_target_x = 9\nwp001_target_y = 6.6\n";
    mrpt::nav::TWaypointSequence seq;
    std::map<size_t, nav::TWaypointTag> tags;
    test::writeFile(d + "/wp.ini", head + "wp000_speed_ratio = 0.4\n");
    try {
        nav::readWaypointFile(d + "/wp.ini", 0.3, seq, tags);
        ADD_FAILURE() << "accepted";
    } catch (const common::CBadInputError& e) {
        EXPECT_EQ(
            std::string(e.what()).rfind(d + "/wp.ini: [Waypoints] wp000_speed_ratio = "
                                            "'0.4': only 1: MRPT 2.5.8 slows to it only "
                                            "within 0.1 m of the waypoint",
                                        0),
            0u)
            << e.what();
    }
    test::writeFile(d + "/wp.ini", head + "wp000_speed_ratio = 1\n");
    nav::readWaypointFile(d + "/wp.ini", 0.3, seq, tags);
    ASSERT_EQ(seq.waypoints.size(), 2u);
    EXPECT_DOUBLE_EQ(seq.waypoints[0].speed_ratio, 1.0);
    EXPECT_EQ(seq.waypoints[0].target_frame_id, "map");
    EXPECT_DOUBLE_EQ(seq.waypoints[1].speed_ratio, 1.0);
}

TEST(WaypointFile, TheDocumentedExampleLoads) {
    // config/risknav-navigate.ini documents the route_file keys with an
    // example (the ';   ' lines after "route_file:"): it is what the reader
    // takes.
    std::string example;
    bool in = false;
    for (const auto& line :
         test::readLines(test::sourcePath("config/risknav-navigate.ini"))) {
        if (line.rfind("; route_file:", 0) == 0)
            in = true;
        else if (in && line.rfind(";   ", 0) == 0)
            example += line.substr(4) + "\n";
        else if (in && !example.empty())
            break;
    }
    ASSERT_NE(example.find("[Waypoints]"), std::string::npos) << example;
    const std::string d = test::freshDir("wpdoc");
    test::writeFile(d + "/route.ini", example);
    mrpt::nav::TWaypointSequence seq;
    std::map<size_t, nav::TWaypointTag> tags;
    nav::readWaypointFile(d + "/route.ini", 0.3, seq, tags);
    ASSERT_EQ(seq.waypoints.size(), 2u);
    EXPECT_DOUBLE_EQ(seq.waypoints[0].target.x, 9.0);
    EXPECT_DOUBLE_EQ(seq.waypoints[1].target.y, 6.6);
    EXPECT_DOUBLE_EQ(seq.waypoints[0].allowed_distance, 0.5);
    EXPECT_FALSE(seq.waypoints[1].allow_skip);
    ASSERT_EQ(tags.count(1), 1u);
    EXPECT_EQ(tags.at(1).kind, "viewpoint");
}

TEST(EscapeHeading, AgreesWithASweepOfAllHeadings) {
    // Against brute force: 7,200 headings, each checked against every point;
    // the function's answer is admissible and no sampled admissible heading
    // within maxOff is nearer the preferred one.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ang(-M_PI, M_PI), rad(0.2, 0.4);
    int found = 0, boxed = 0;
    for (int trial = 0; trial < 300; trial++) {
        std::vector<mrpt::math::TPoint2D> pts;
        const int n = 1 + trial % 4;
        const double centre = ang(rng);  // points clustered, as a post or a wall is
        for (int k = 0; k < n; k++) {
            const double b = centre + 0.6 * ang(rng) / M_PI;
            pts.emplace_back(rad(rng) * std::cos(b), rad(rng) * std::sin(b));
        }
        const double preferred = ang(rng), extra = trial % 2 ? 0.0 : 0.2,
                     maxOff = trial % 3 ? M_PI : 1.4;
        auto leaves = [&](double h) {
            for (const auto& p : pts)
                if (std::cos(h) * p.x + std::sin(h) * p.y >=
                    -std::sin(extra) * std::hypot(p.x, p.y))
                    return false;
            return true;
        };
        double bestOff = 1e9;
        for (int s = 0; s < 7200; s++) {
            const double h = -M_PI + 2 * M_PI * s / 7200;
            const double off = std::abs(mrpt::math::wrapToPi(h - preferred));
            if (off <= maxOff && leaves(h))
                bestOff = std::min(bestOff, off);
        }
        const auto e = nav::escapeHeading(pts, preferred, extra, maxOff);
        if (!e) {
            boxed++;
            EXPECT_GT(bestOff, 1e8) << "trial " << trial;  // the sweep found none either
            continue;
        }
        found++;
        EXPECT_TRUE(leaves(*e)) << "trial " << trial;
        const double off = std::abs(mrpt::math::wrapToPi(*e - preferred));
        EXPECT_LE(off, maxOff + 1e-9);
        EXPECT_LE(off, bestOff + 2e-6) << "trial " << trial;  // 1e-6 past an arc end
        EXPECT_GT(off, bestOff - 2 * M_PI / 7200 - 1e-6) << "trial " << trial;
    }
    EXPECT_GT(found, 150);  // both outcomes were exercised
    EXPECT_GT(boxed, 5);
    // none to leave: no escape; a door post ahead-left (as in rooms seed 8,
    // target straight ahead): turned right, just past perpendicular to it
    EXPECT_FALSE(nav::escapeHeading({}, 0.0, 0.0, M_PI));
    const auto e = nav::escapeHeading({{0.33, 0.05}, {0.30, 0.15}}, 0.0, 0.0, M_PI);
    ASSERT_TRUE(e);
    EXPECT_NEAR(*e, std::atan2(0.05, 0.33) - M_PI / 2, 1e-5);
}
