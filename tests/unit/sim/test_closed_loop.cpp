#include <risknav/sim/CClosedLoop.h>
#include <risknav/sim/CSimWorld.h>

#include <gtest/gtest.h>
#include "sim_fixtures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace risknav::sim;
using mrpt::math::TPose2D;

namespace {
using risknav::test::emptyRoom;

// A world whose robot reaches any commanded speed within one step.
void makeWorld(CSimWorld& w, const TPose2D& start) {
    w.robot.accel = w.robot.decel = 20;
    w.robot.w_accel_deg = 10000;
    w.odometry.options.error_model = "none";
    w.setMap(emptyRoom());
    w.reset(start, 1);
}

// A synthetic controller: constant speed v for `cycles` cycles, then it ends
// the loop; every hook call is counted.
struct TConstantSpeed : public CClosedLoop {
    TConstantSpeed(CSimWorld& w, const TOptions& o, double speed, int n)
        : CClosedLoop(w, o), v(speed), cyclesToRun(n) {}
    double v;
    int cyclesToRun;
    int cycleCalls = 0, stepsCalls = 0, commands = 0, stepped = 0, cycleEnds = 0;
    std::vector<double> cycleTimes, stepTimes;
    std::vector<TPose2D> poses;  // after every sub-step, as onStepped() saw it
    bool onCycle(int cycle) override {
        EXPECT_EQ(cycle, cycleCalls);
        cycleCalls++;
        cycleTimes.push_back(world.time());
        return cycle < cyclesToRun;
    }
    void onCycleSteps(int) override { stepsCalls++; }
    void onSubStep(int, int k) override {
        EXPECT_EQ(k, commands % options.steps_per_cycle);
        commands++;
        world.command(v, 0);
    }
    void onStepped(int, int, const TPose2D& now) override {
        stepped++;
        stepTimes.push_back(world.time());
        poses.push_back(now);
        EXPECT_EQ(now.x, world.truePose().x);
    }
    void onCycleEnd(int) override { cycleEnds++; }
};
}  // namespace

TEST(ClosedLoop, ConstantSpeedForNCyclesStepsAndRecordsEachCycle) {
    CSimWorld w;
    makeWorld(w, TPose2D(-5, 0, 0));
    CClosedLoop::TOptions o;
    o.sim_dt = 0.05;
    o.steps_per_cycle = 4;
    TConstantSpeed loop(w, o, 0.5, 10);
    EXPECT_EQ(loop.run(), CClosedLoop::TEnd::Controller);
    // ten driven cycles, then the eleventh is recorded and ends the loop
    EXPECT_EQ(loop.cycleCalls, 11);
    EXPECT_EQ(loop.cycles(), 11);
    EXPECT_EQ(loop.stepsCalls, 10);
    EXPECT_EQ(loop.cycleEnds, 10);
    EXPECT_EQ(loop.commands, 40);
    EXPECT_EQ(loop.stepped, 40);
    EXPECT_NEAR(w.time(), 40 * 0.05, 1e-12);
    for (size_t c = 0; c < loop.cycleTimes.size(); c++)
        EXPECT_NEAR(loop.cycleTimes[c], c * 4 * 0.05, 1e-12);
    // a straight line at 0.5 m/s for 2 s
    EXPECT_NEAR(loop.travelled(), 1.0, 1e-9);
    EXPECT_NEAR(w.truePose().x, -4.0, 1e-9);
    EXPECT_EQ(loop.safety.collisionsStatic(), 0);
}

TEST(ClosedLoop, DurationMaxEndsTheLoopAfterTheRecordedCycle) {
    CSimWorld w;
    makeWorld(w, TPose2D(0, 0, 0));
    CClosedLoop::TOptions o;
    o.sim_dt = 0.1;
    o.steps_per_cycle = 5;
    o.duration_max = 2.0;  // four cycles of 0.5 s
    TConstantSpeed loop(w, o, 0.2, 1000);
    EXPECT_EQ(loop.run(), CClosedLoop::TEnd::Timeout);
    EXPECT_EQ(loop.cycleCalls, 5);  // t = 0, 0.5, 1, 1.5 driven; t = 2 recorded
    EXPECT_EQ(loop.stepsCalls, 4);
    EXPECT_EQ(loop.stepped, 20);
    EXPECT_NEAR(loop.cycleTimes.back(), 2.0, 1e-12);
    EXPECT_NEAR(w.time(), 2.0, 1e-12);
}

TEST(ClosedLoop, ControllerEndsTheLoopBeforeTheWorldMoves) {
    CSimWorld w;
    makeWorld(w, TPose2D(0, 0, 0));
    CClosedLoop::TOptions o;
    TConstantSpeed loop(w, o, 0.5, 0);
    EXPECT_EQ(loop.run(), CClosedLoop::TEnd::Controller);
    EXPECT_EQ(loop.cycleCalls, 1);
    EXPECT_EQ(loop.stepped, 0);
    EXPECT_EQ(w.time(), 0.0);
    EXPECT_EQ(loop.travelled(), 0.0);
}

TEST(ClosedLoop, MonitorSeesEverySubStep) {
    // Into the wall at x = 10: the collision happens between two cycle
    // boundaries (10 sub-steps a cycle), and the monitor must time it at
    // the sub-step it happened and take every sub-step's gap.
    CSimWorld w;
    makeWorld(w, TPose2D(8.5, 0, 0));
    CClosedLoop::TOptions o;
    o.sim_dt = 0.05;
    o.steps_per_cycle = 10;
    TConstantSpeed loop(w, o, 0.7, 8);
    loop.run();
    ASSERT_EQ(loop.safety.collisionsStatic(), 1);
    double firstHit = -1, minGap = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < loop.poses.size(); k++) {
        const double gap =
            w.pointClearance(loop.poses[k].x, loop.poses[k].y) - w.robot.radius;
        minGap = std::min(minGap, gap);
        if (gap < 0 && firstHit < 0)
            firstHit = loop.stepTimes[k];
    }
    ASSERT_GT(firstHit, 0);
    const auto& ev = loop.safety.events();
    ASSERT_FALSE(ev.empty());
    EXPECT_EQ(ev.front().kind, "collision");
    EXPECT_EQ(ev.front().t, firstHit);
    // not on a cycle boundary: only a per-sub-step monitor times it so
    const double cycleLen = o.sim_dt * o.steps_per_cycle;
    EXPECT_GT(std::abs(firstHit / cycleLen - std::round(firstHit / cycleLen)), 1e-6);
    EXPECT_EQ(loop.safety.minGapStatic(), minGap);
}

TEST(ClosedLoop, TimeAsSumStampsTheStepStartPlusDt) {
    for (const bool sum : {false, true}) {
        CSimWorld w;
        makeWorld(w, TPose2D(9.0, 0, 0));
        CClosedLoop::TOptions o;
        o.sim_dt = 0.05;
        o.steps_per_cycle = 3;
        o.time_as_sum = sum;
        TConstantSpeed loop(w, o, 0.7, 10);
        loop.run();
        ASSERT_FALSE(loop.safety.events().empty());
        const double t = loop.safety.events().front().t;
        // the step that hit: its end time, either way within rounding
        const auto it = std::find_if(loop.stepTimes.begin(), loop.stepTimes.end(),
                                     [&](double s) { return std::abs(s - t) < 1e-9; });
        ASSERT_NE(it, loop.stepTimes.end());
        if (!sum)
            EXPECT_EQ(t, *it);
        else
            EXPECT_EQ(t, (it == loop.stepTimes.begin() ? 0.0 : *(it - 1)) + o.sim_dt);
    }
}
