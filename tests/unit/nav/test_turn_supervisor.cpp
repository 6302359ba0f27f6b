// CTurnSupervisor on synthetic poses, targets, points and times: no MRPT
// engine, no world.
#include <risknav/nav/CTurnSupervisor.h>

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
using risknav::nav::CTurnSupervisor;

namespace {
constexpr double kDeg = M_PI / 180;
constexpr double kCycle = 0.2;  // [s] a navigation cycle

CTurnSupervisor::TInput input(const TPose2D& pose, const TPoint2D& target, double now,
                              double speed = 0) {
    CTurnSupervisor::TInput in;
    in.pose = pose;
    in.target = target;
    in.now = now;
    in.speed = speed;
    return in;
}

/** Turns the robot as the supervisor commands, a cycle at a time, until it
 * lets MRPT step (or `maxCycles`); the cycles it turned. */
int turnUntilDone(CTurnSupervisor& s, TPose2D& pose, const TPoint2D& target, double& t,
                  int maxCycles = 200) {
    for (int k = 0; k < maxCycles; k++) {
        const auto turn = s.step(input(pose, target, t));
        if (!turn)
            return k;
        pose.phi = mrpt::math::wrapToPi(pose.phi + turn->angVel * kCycle);
        t += kCycle;
    }
    return maxCycles;
}
}  // namespace

TEST(TurnSupervisor, TargetToTheSideOfAStandingRobotIsTurnedToFirst) {
    CTurnSupervisor s;  // start_turn_deg 45, turn_rate_deg 30
    // 90 deg to the left: turned left at the turn rate, MRPT not asked
    const auto left = s.step(input(TPose2D(0, 0, 0), TPoint2D(0, 3), 100));
    ASSERT_TRUE(left);
    EXPECT_NEAR(left->angVel, 30 * kDeg, 1e-12);
    EXPECT_FALSE(left->unsticking);
    EXPECT_NE(left->reason.find("start_turn_deg"), std::string::npos) << left->reason;
    EXPECT_TRUE(s.turning());
    // and to the right
    CTurnSupervisor r;
    const auto right = r.step(input(TPose2D(0, 0, 0), TPoint2D(0, -3), 100));
    ASSERT_TRUE(right);
    EXPECT_NEAR(right->angVel, -30 * kDeg, 1e-12);
    // a target ahead is MRPT's at once
    CTurnSupervisor ahead;
    EXPECT_FALSE(ahead.step(input(TPose2D(0, 0, 0), TPoint2D(3, 0.5), 100)));
}

TEST(TurnSupervisor, TurnEndsWithinAThirdOfItsAngle) {
    CTurnSupervisor s;
    TPose2D pose(0, 0, 0);
    double t = 100;
    const TPoint2D target(0, 3);
    const int cycles = turnUntilDone(s, pose, target, t);
    // 90 deg turned down to at most 15 deg (45 / 3) at 6 deg a cycle
    EXPECT_GT(cycles, 5);
    EXPECT_LT(cycles, 200);
    const double off = std::abs(mrpt::math::wrapToPi(M_PI / 2 - pose.phi)) / kDeg;
    EXPECT_LE(off, 15 + 1e-9);
    EXPECT_GT(off, 15 - 6 - 1e-9);  // it ended at the first cycle within
    EXPECT_FALSE(s.turning());
}

TEST(TurnSupervisor, MovingRobotIsTurnedOnlyForATargetBehind) {
    CTurnSupervisor s;  // turn_in_place_deg 100
    // moving at 0.3 m/s, 90 deg off: MRPT's (no start turn)
    EXPECT_FALSE(s.step(input(TPose2D(0, 0, 0), TPoint2D(0, 3), 100, 0.3)));
    // 135 deg off: beyond turn_in_place_deg, turned even while moving
    const auto behind = s.step(input(TPose2D(0, 0, 0), TPoint2D(-3, 3), 100.2, 0.3));
    ASSERT_TRUE(behind);
    EXPECT_GT(behind->angVel, 0);
    EXPECT_NE(behind->reason.find("turn_in_place_deg"), std::string::npos);
    // all off: MRPT's always
    CTurnSupervisor off;
    off.options.turn_in_place_deg = off.options.start_turn_deg = 0;
    off.options.unstick_time = 0;
    EXPECT_FALSE(off.step(input(TPose2D(0, 0, 0), TPoint2D(-3, 0.1), 100)));
}

TEST(TurnSupervisor, RobotStillForTheUnstickTimeIsTurnedToItsTarget) {
    CTurnSupervisor s;  // unstick_time 5 s, unstick_heading_deg 15
    const TPose2D pose(1, 1, 0);
    const TPoint2D target(4, 1 + 3 * std::tan(30 * kDeg));  // 30 deg off: no start turn
    for (int k = 0; k < 25; k++)                            // 0 .. 4.8 s
        EXPECT_FALSE(s.step(input(pose, target, 50 + k * kCycle))) << "cycle " << k;
    const auto turn = s.step(input(pose, target, 50 + 5));
    ASSERT_TRUE(turn);
    EXPECT_TRUE(turn->unsticking);
    EXPECT_GT(turn->angVel, 0);
    EXPECT_NE(turn->reason.find("30 deg off after 5 s without motion"), std::string::npos)
        << turn->reason;
}

TEST(TurnSupervisor, MovingOrTurningRobotIsNotStuck) {
    CTurnSupervisor s;
    const TPoint2D target(10, 10 * std::tan(30 * kDeg));
    // 6 cm a cycle: never still for 5 s
    for (int k = 0; k < 100; k++)
        EXPECT_FALSE(
            s.step(input(TPose2D(0.06 * k, 0, 0), target, 50 + k * kCycle, 0.3)));
    // turning 6 deg a cycle on the spot (dithering more than 5 deg), the
    // target 24-30 deg off
    CTurnSupervisor d;
    for (int k = 0; k < 100; k++)
        EXPECT_FALSE(d.step(
            input(TPose2D(0, 0, (k % 2 ? 6 : 0) * kDeg), target, 50 + k * kCycle, 0.0)));
}

TEST(TurnSupervisor, StuckRobotFacingPointsAtItsShapeTurnsAwayFromThem) {
    for (const double side : {1.0, -1.0}) {
        CTurnSupervisor s;
        const TPose2D pose(0, 0, 0);
        const TPoint2D target(5, 0);  // straight ahead
        const std::vector<TPoint2D> post{TPoint2D(0.30, 0.10 * side)};
        auto in = [&](double t) {
            auto i = input(pose, target, t);
            i.pointsNearShape = [&] { return post; };
            return i;
        };
        for (int k = 0; k < 25; k++)
            EXPECT_FALSE(s.step(in(k * kCycle)));
        const auto turn = s.step(in(5));
        ASSERT_TRUE(turn);
        EXPECT_TRUE(turn->unsticking);
        // away from the post's side
        EXPECT_LT(turn->angVel * side, 0) << "post on side " << side;
        EXPECT_NE(turn->reason.find("obstacle at MRPT's robot shape"), std::string::npos)
            << turn->reason;
        // the turn holds its escape heading: the post's bearing (18 deg)
        // + 90 deg, i.e. -72 deg (mirrored), ended within 5 deg of it
        TPose2D p = pose;
        double t = 5;
        for (int k = 0; k < 100; k++) {
            auto i = in(t);
            i.pose = p;
            const auto tr = s.step(i);
            if (!tr)
                break;
            p.phi += tr->angVel * kCycle;
            t += kCycle;
        }
        const double expected = -side * (90 - std::atan2(0.10, 0.30) / kDeg);
        EXPECT_NEAR(p.phi / kDeg, expected, 6) << "side " << side;
    }
}

TEST(TurnSupervisor, StuckRobotWithNothingAtItsShapeIsLeftToMrpt) {
    CTurnSupervisor s;
    for (int k = 0; k <= 40; k++) {
        auto i = input(TPose2D(0, 0, 0), TPoint2D(5, 0), k * kCycle);
        i.pointsNearShape = [] { return std::vector<TPoint2D>{}; };
        EXPECT_FALSE(s.step(i));
    }
}

TEST(TurnSupervisor, AtMostThreeUnstickTurnsPerTargetUntilNearer) {
    CTurnSupervisor s;
    TPose2D pose(0, 0, 0);
    const TPoint2D target(5, 0);
    double t = 0;
    int turns = 0;
    // each time: still with the target 30 deg off, turned, then pushed back
    // 30 deg off again
    for (int round = 0; round < 5; round++) {
        pose.phi = -30 * kDeg;
        for (int k = 0; k < 100; k++, t += kCycle) {
            const auto turn = s.step(input(pose, target, t));
            if (turn) {
                turns++;
                turnUntilDone(s, pose, target, t);
                break;
            }
        }
        t += kCycle;
    }
    EXPECT_EQ(turns, CTurnSupervisor::kMaxUnstickTurns);
    // 0.5 m nearer: counted again
    pose = TPose2D(0.6, 0, -30 * kDeg);
    bool again = false;
    for (int k = 0; k < 100 && !again; k++, t += kCycle)
        again = s.step(input(pose, target, t)).has_value();
    EXPECT_TRUE(again);
}

TEST(TurnSupervisor, GuidePointPausedForARobotStuckWhileGuided) {
    CTurnSupervisor s;
    const TPoint2D target(5, 0), guide(2, 0.2);
    int asked = 0;
    auto in = [&](const TPose2D& p, double t) {
        auto i = input(p, target, t);
        i.guidePoint = [&]() -> std::optional<TPoint2D> {
            asked++;
            if (s.guidePaused())
                return std::nullopt;
            return guide;
        };
        return i;
    };
    for (int k = 0; k < 25; k++) {
        s.step(in(TPose2D(0, 0, 0), k * kCycle));
        EXPECT_FALSE(s.guidePaused());
    }
    EXPECT_GT(asked, 0);  // the aim was the guide point
    s.step(in(TPose2D(0, 0, 0), 5));
    EXPECT_TRUE(s.guidePaused());
    // moved 0.3 m: still paused; 0.6 m from where it paused: not
    s.step(in(TPose2D(0.3, 0, 0), 5.2));
    EXPECT_TRUE(s.guidePaused());
    s.step(in(TPose2D(0.6, 0, 0), 5.4));
    EXPECT_FALSE(s.guidePaused());
}

TEST(TurnSupervisor, AimIsTheGuidePointWhenGiven) {
    CTurnSupervisor s;
    // the target ahead, the guide point 90 deg left: turned to the guide
    auto i = input(TPose2D(0, 0, 0), TPoint2D(5, 0), 10);
    i.guidePoint = [] { return std::optional<TPoint2D>(TPoint2D(0, 2)); };
    const auto turn = s.step(i);
    ASSERT_TRUE(turn);
    EXPECT_GT(turn->angVel, 0);
}

TEST(TurnSupervisor, PointsNearShapeKeepsThoseWithinTheShapeAndItsEdge) {
    mrpt::maps::CSimplePointsMap m;
    m.insertPoint(0.30, 0);   // inside a 0.35 m shape
    m.insertPoint(0, 0.37);   // at its edge (within 3 cm)
    m.insertPoint(-0.39, 0);  // outside
    m.insertPoint(1.0, 1.0);  // far
    const auto near = CTurnSupervisor::pointsNearShape(m, 0.35);
    ASSERT_EQ(near.size(), 2u);
    EXPECT_NEAR(near[0].x, 0.30, 1e-6);
    EXPECT_NEAR(near[1].y, 0.37, 1e-6);
}
