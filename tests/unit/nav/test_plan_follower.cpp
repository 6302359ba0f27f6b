// CPlanFollower's final approach on synthetic poses and points: no MRPT
// engine, no world.
#include <risknav/nav/CPlanFollower.h>

#include <gtest/gtest.h>

#include <vector>

using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
using risknav::nav::CPlanFollower;

namespace {
const CPlanFollower::TBody kBody{0.35, 0.30};  // MRPT's shape, [Robot] radius
}

TEST(PlanFollower, BodyFloorIsTheRobotWithItsSensingErrorWithinTheShape) {
    CPlanFollower f;                                      // plan_follow_margin 0.05
    EXPECT_NEAR(f.bodyFloor(kBody), 0.30, 1e-12);         // 0.35 - 0.05
    EXPECT_NEAR(f.bodyFloor({0.50, 0.30}), 0.32, 1e-12);  // 0.30 + 0.02
}

TEST(PlanFollower, EndInsideTheShapeIsDrivenTo) {
    CPlanFollower f;  // final_approach_speed 0.1
    int sensed = 0;
    const auto none = [&] {
        sensed++;
        return std::vector<TPoint2D>{};
    };
    // 0.3 m ahead, allowed 0.15: inside the shape's 0.35 + 0.1, driven to
    const auto d = f.finalApproach(TPose2D(0, 0, 0), TPoint2D(0.3, 0), 0.15, kBody, none);
    ASSERT_TRUE(d);
    EXPECT_STREQ(d->mode, "final_approach");
    EXPECT_GT(d->cmd.v, 0);
    EXPECT_LE(d->cmd.v, 0.1 + 1e-12);
    EXPECT_EQ(sensed, 1);
    // to the side: turned to first
    const auto t = f.finalApproach(TPose2D(0, 0, 0), TPoint2D(0, 0.3), 0.15, kBody, none);
    ASSERT_TRUE(t);
    EXPECT_EQ(t->cmd.v, 0);
    EXPECT_GT(t->cmd.w, 0);
    // MRPT's: farther than the shape + 0.1 m, within the allowed distance,
    // or off (nothing sensed for them)
    EXPECT_FALSE(f.finalApproach(TPose2D(0, 0, 0), TPoint2D(0.5, 0), 0.15, kBody, none));
    EXPECT_FALSE(f.finalApproach(TPose2D(0, 0, 0), TPoint2D(0.1, 0), 0.15, kBody, none));
    CPlanFollower off;
    off.options.final_approach_speed = 0;
    EXPECT_FALSE(
        off.finalApproach(TPose2D(0, 0, 0), TPoint2D(0.3, 0), 0.15, kBody, none));
    EXPECT_EQ(sensed, 2);
}

TEST(PlanFollower, BlockedEndIsNotTriedAgainUntilTheRobotMoved) {
    CPlanFollower f;
    int sensed = 0;
    // a post between the robot and the end, nearer than its body
    const auto post = [&] {
        sensed++;
        return std::vector<TPoint2D>{TPoint2D(0.25, 0)};
    };
    const TPoint2D end(0.4, 0);
    EXPECT_FALSE(f.finalApproach(TPose2D(0, 0, 0), end, 0.15, kBody, post));
    EXPECT_EQ(sensed, 1);
    // 5 cm on: not tried (MRPT's and the unstick turns' turn)
    EXPECT_FALSE(f.finalApproach(TPose2D(0.05, 0, 0), end, 0.15, kBody, post));
    EXPECT_EQ(sensed, 1);
    // 0.15 m from where it was blocked: tried again
    const auto free = [&] {
        sensed++;
        return std::vector<TPoint2D>{};
    };
    EXPECT_TRUE(f.finalApproach(TPose2D(0.15, 0, 0), end, 0.15, kBody, free));
    EXPECT_EQ(sensed, 2);
}
