// MRPT's own reactive navigator drives a risknav world through
// CSimRobotInterface: the interface, the world's laser (people included) and
// its physics are what MRPT's CReactiveNavigationSystem sees and commands.
#include <risknav/common/CIniConfig.h>
#include <risknav/sim/CSafetyMonitor.h>
#include <risknav/sim/CSimRobotInterface.h>
#include <risknav/sim/CSimWorld.h>
#include <test_support.h>

#include <mrpt/config/CConfigFile.h>
#include <mrpt/math/CPolygon.h>
#include <mrpt/nav/reactive/CReactiveNavigationSystem.h>
#include <mrpt/system/filesystem.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav;
using mrpt::math::TPose2D;

namespace {
struct TNavResult {
    bool reached = false;
    int state = -1, steps = 0;
    double time = 0, goalError = 0;
    int collisions = 0, walkersSeen = 0;
    double minGapStatic = 0;
};

TNavResult navigateOffice(uint64_t seed, bool people) {
    common::CIniConfig cfg(test::sourcePath("datasets/office/world.ini"));
    sim::CSimWorld world;
    world.loadFromConfigFile(cfg);
    if (!people)
        world.agents.walkers.clear();
    world.reset(TPose2D(3.0, 3.0, M_PI / 2), seed);
    sim::CSimRobotInterface robot(world);
    robot.setMinLoggingLevel(mrpt::system::LVL_ERROR);

    mrpt::nav::CReactiveNavigationSystem nav(robot, false, false);
    nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    const_cast<mrpt::system::CTimeLogger&>(nav.getDelaysTimeLogger()).disable();
    mrpt::config::CConfigFile navCfg(
        mrpt::system::find_mrpt_shared_dir() +
        "config_files/navigation-ptgs/reactive2d_config.ini");
    navCfg.discardSavingChanges();
    nav.loadConfigFile(navCfg);
    nav.params_abstract_ptg_navigator.ptg_cache_files_directory = test::freshDir("ptg");
    // The navigator plans for the world's robot: a disc of its radius.
    mrpt::math::CPolygon shape;
    for (int i = 0; i < 16; i++)
        shape.AddVertex(world.robot.radius * std::cos(i * M_PI / 8),
                        world.robot.radius * std::sin(i * M_PI / 8));
    nav.changeRobotShape(shape);
    nav.initialize();

    // Out of the start room, along the corridor past the walkers and the
    // clutter, into the far room: MRPT waypoints (CWaypointsNavigator).
    mrpt::nav::TWaypointSequence wps;
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{
             {3.0, 6.6}, {9.0, 6.6}, {16.5, 6.6}, {16.5, 4.6}, {15.0, 2.5}})
        wps.waypoints.emplace_back(x, y, 0.3, false);
    nav.navigateWaypoints(wps);

    sim::CSafetyMonitor safety;
    mrpt::Clock::setSimulatedTime(mrpt::Clock::fromDouble(1.6e9));
    mrpt::Clock::setActiveClock(mrpt::Clock::Simulated);
    TNavResult r;
    const double dt = 0.05;
    for (r.steps = 0; r.steps < 3000; r.steps++) {  // 10 min of simulated time at most
        nav.navigationStep();
        const auto st = nav.getCurrentState();
        if (st == mrpt::nav::CAbstractNavigator::IDLE ||
            st == mrpt::nav::CAbstractNavigator::NAV_ERROR)
            break;
        for (int k = 0; k < 4; k++) {  // 0.2 s per navigation cycle
            world.step(dt);
            safety.update(world.time(), world.truePose(), world.robot.radius,
                          world.agents,
                          world.clearance(world.truePose().x, world.truePose().y));
        }
        mrpt::Clock::setSimulatedTime(mrpt::Clock::fromDouble(1.6e9 + world.time()));
    }
    mrpt::Clock::setActiveClock(mrpt::Clock::Realtime);
    r.state = int(nav.getCurrentState());
    r.reached = nav.getWaypointNavStatus().final_goal_reached;
    r.time = world.time();
    const auto p = world.truePose();
    r.goalError = std::hypot(p.x - 15.0, p.y - 2.5);
    r.collisions = safety.collisions() + safety.collisionsStatic();
    r.minGapStatic = safety.minGapStatic();
    for (const auto& e : world.agentEvents())
        r.walkersSeen += e.kind == "spawn";
    return r;
}
}  // namespace

TEST(MrptNavigator, CrossesTheOfficeWithoutCollision) {
    const auto r = navigateOffice(11, false);
    std::cout << "[nav] state " << r.state << ", " << r.time << " s, goal error "
              << r.goalError << " m, min wall gap " << r.minGapStatic << " m\n";
    EXPECT_TRUE(r.reached);
    EXPECT_EQ(r.state, int(mrpt::nav::CAbstractNavigator::IDLE));
    EXPECT_LT(r.goalError, 0.4);
    EXPECT_EQ(r.collisions, 0);
}

TEST(MrptNavigator, CrossesTheOfficeWithWalkersWithoutCollision) {
    const auto r = navigateOffice(11, true);
    std::cout << "[nav+people] state " << r.state << ", " << r.time << " s, goal error "
              << r.goalError << " m, walkers " << r.walkersSeen << "\n";
    EXPECT_GT(r.walkersSeen, 0);
    EXPECT_TRUE(r.reached);
    EXPECT_LT(r.goalError, 0.4);
    EXPECT_EQ(r.collisions, 0);
}
