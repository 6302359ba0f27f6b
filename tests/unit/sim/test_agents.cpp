#include <risknav/common/CBadInputError.h>
#include <risknav/sim/CAgentsSim.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::sim;
using mrpt::math::TPose2D;

namespace {
CAgentsSim::TDoorPedestrian door(const std::string& emergence) {
    CAgentsSim::TDoorPedestrian d;
    d.section = "DoorPedestrian1";
    const double seg[4] = {4.6, 2, 5.4, 2};
    std::copy(seg, seg + 4, d.door);
    d.path = {{5, 2.5}, {5, -1.5}};  // 4 m straight down across y = 0
    d.emergence = emergence;
    return d;
}

size_t count(const std::vector<TAgentEvent>& ev, const std::string& kind) {
    return size_t(std::count_if(ev.begin(), ev.end(),
                                [&](const auto& e) { return e.kind == kind; }));
}

const TPose2D kFarRobot(-50, -50, 0);
}  // namespace

TEST(CAgentsSim, ScheduledPersonWalksItsPathAtItsSpeedAndLeaves) {
    CAgentsSim a;
    auto d = door("schedule");
    d.schedule = {1.0};
    a.doors.push_back(d);
    a.reset(1);
    std::vector<TAgentEvent> ev;
    double t = 0;
    const double dt = 0.05;
    for (int k = 0; k < 60; k++)
        a.step(t += dt, dt, kFarRobot, 0.25, ev);  // t = 3.0
    ASSERT_EQ(count(ev, "emerge"), 1u);
    EXPECT_NEAR(ev[0].t, 1.0, 1e-9);
    ASSERT_EQ(a.discs().size(), 1u);
    // Emerged at t = 1.0 at (5, 2.5): 2 s at 0.8 m/s later it is 1.6 m down the path.
    EXPECT_NEAR(a.discs()[0].y, 2.5 - 1.6, 0.8 * dt + 1e-9);
    for (int k = 0; k < 100; k++)
        a.step(t += dt, dt, kFarRobot, 0.25, ev);
    EXPECT_EQ(count(ev, "leave"), 1u);
    EXPECT_TRUE(a.discs().empty());
}

TEST(CAgentsSim, PeopleWalkAroundARobotOnTheirPath) {
    CAgentsSim a;
    auto d = door("schedule");
    d.schedule = {0.0};
    a.doors.push_back(d);
    a.reset(1);
    const TPose2D robot(5.0, 0.0, 0.0);  // standing right on the path
    std::vector<TAgentEvent> ev;
    double t = 0, minGap = 1e9;
    for (int k = 0; k < 400 && count(ev, "leave") == 0; k++) {
        a.step(t += 0.05, 0.05, robot, 0.25, ev);
        for (const auto& disc : a.discs())
            minGap = std::min(
                minGap, std::hypot(disc.x - robot.x, disc.y - robot.y) - disc.r - 0.25);
    }
    EXPECT_EQ(count(ev, "leave"), 1u);
    EXPECT_EQ(count(ev, "give_up"), 0u);
    EXPECT_GE(minGap, 0.0);       // never overlapped the robot
    EXPECT_LT(t, 4.0 / 0.8 + 3);  // and the detour cost little time
}

TEST(CAgentsSim, TriggerFiresOncePerPass) {
    CAgentsSim a;
    auto d = door("trigger");
    d.trigger_distance = 2.5;
    d.trigger_probability = 1.0;
    d.path = {{5, 2.5}, {5, 2.0}};  // short: the door is free again quickly
    a.doors.push_back(d);
    a.reset(1);
    std::vector<TAgentEvent> ev;
    double t = 0;
    auto stay = [&](TPose2D robot, int steps) {
        for (int k = 0; k < steps; k++)
            a.step(t += 0.05, 0.05, robot, 0.25, ev);
    };
    stay({0, 0, 0}, 40);  // 5.4 m from the door: nothing
    EXPECT_EQ(count(ev, "emerge"), 0u);
    stay({4, 0, 0}, 100);  // within 2.5 m: one person, however long the robot stays
    EXPECT_EQ(count(ev, "emerge"), 1u);
    stay({0, 0, 0}, 10);  // away (re-arms), and back
    stay({5, 0.5, 0}, 10);
    EXPECT_EQ(count(ev, "emerge"), 2u);
}

TEST(CAgentsSim, PoissonRate) {
    CAgentsSim a;
    auto d = door("poisson");
    d.rate_per_min = 6;  // one every 10 s on average
    d.path = {{5, 2.5}, {5, 2.4}};
    a.doors.push_back(d);
    a.reset(42);
    std::vector<TAgentEvent> ev;
    double t = 0;
    for (int k = 0; k < 20000; k++)
        a.step(t += 0.05, 0.05, kFarRobot, 0.25, ev);  // 1000 s
    // Poisson(100): sd 10.
    EXPECT_NEAR(double(count(ev, "emerge")), 100.0, 35.0);
}

TEST(CAgentsSim, WalkersSpawnPeriodicallyAtSpeedsInRange) {
    CAgentsSim a;
    CAgentsSim::TWalker w;
    w.section = "CorridorWalker1";
    w.path = {{0, 0}, {100, 0}};
    w.period = 10;
    w.phase = 2;
    a.walkers.push_back(w);
    a.reset(3);
    std::vector<TAgentEvent> ev;
    double t = 0;
    for (int k = 0; k < 1000; k++)
        a.step(t += 0.05, 0.05, kFarRobot, 0.25, ev);  // 50 s
    ASSERT_EQ(count(ev, "spawn"), 5u);                 // at 2, 12, 22, 32, 42 s
    EXPECT_NEAR(ev[0].t, 2.0, 0.05 + 1e-9);
    for (const auto& disc : a.discs()) {
        const double age = 50.0 - (2.0 + 10.0 * (disc.objectId)), speed = disc.x / age;
        EXPECT_GE(speed, 1.6 - 0.05);
        EXPECT_LE(speed, 2.0 + 0.05);
    }
}

TEST(CAgentsSim, ConfigErrors) {
    using risknav::common::CBadInputError;
    CAgentsSim a;
    EXPECT_THROW(a.loadFromConfigFile(mrpt::config::CConfigFileMemory(
                     "[DoorPedestrian1]\npath = 0 0 1 1\n")),
                 CBadInputError);  // no door
    EXPECT_THROW(a.loadFromConfigFile(mrpt::config::CConfigFileMemory(
                     "[CorridorWalker1]\npath = 0 0 1\n")),
                 CBadInputError);  // odd coordinates
    EXPECT_THROW(
        a.loadFromConfigFile(mrpt::config::CConfigFileMemory(
            "[CorridorWalker1]\npath = 0 0 1 1\nspeed_min = 2\nspeed_max = 1\n")),
        CBadInputError);
    EXPECT_THROW(
        a.loadFromConfigFile(mrpt::config::CConfigFileMemory(
            "[DoorPedestrian1]\ndoor = 0 0 1 0\npath = 0 0 1 1\nemergence = schedule\n")),
        CBadInputError);  // schedule without times
    a.loadFromConfigFile(
        mrpt::config::CConfigFileMemory("[Clutter2]\nx = 1\ny = 2\nradius = 0.4\n"));
    ASSERT_EQ(a.clutter.size(), 1u);
    EXPECT_TRUE(CAgentsSim::ownsSection("DoorPedestrian12"));
    EXPECT_FALSE(CAgentsSim::ownsSection("DoorPedestrian"));
    EXPECT_FALSE(CAgentsSim::ownsSection("Doors1"));
}
