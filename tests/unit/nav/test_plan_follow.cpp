#include <risknav/nav/plan_follow.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
using risknav::nav::arcClearance;
using risknav::nav::planFollowCommand;

namespace {
std::vector<TPoint2D> straightPlan(double x0, double y0, double x1, double y1) {
    std::vector<TPoint2D> p;
    const int n = 100;
    for (int k = 0; k <= n; k++)
        p.emplace_back(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n);
    return p;
}
/** World points seen from `pose` (the robot frame planFollowCommand takes). */
std::vector<TPoint2D> robotFrame(const TPose2D& pose,
                                 const std::vector<TPoint2D>& world) {
    std::vector<TPoint2D> out;
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    for (const auto& q : world) {
        const double dx = q.x - pose.x, dy = q.y - pose.y;
        out.emplace_back(c * dx + s * dy, -s * dx + c * dy);
    }
    return out;
}
}  // namespace

TEST(PlanFollow, ArcClearanceMatchesTheCircleGeometry) {
    // a point at the centre of the arc's circle stays at its radius
    const double v = 0.2, w = 0.4, r = v / w;  // r = 0.5 m, centre (0, 0.5)
    EXPECT_NEAR(arcClearance({TPoint2D(0, r)}, v, w, 1.0), r, 1e-9);
    // straight: a point beside the way, its foot inside the stretch
    EXPECT_NEAR(arcClearance({TPoint2D(0.6, 0.3)}, 0.2, 0, 1.0), 0.3, 1e-9);
    // and beyond its end: the end pose's distance
    EXPECT_NEAR(arcClearance({TPoint2D(2.0, 0.0)}, 0.2, 0, 1.0), 1.0, 1e-9);
    // against a dense brute force on random arcs and points
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int t = 0; t < 50; t++) {
        const double vv = 0.1 + 0.2 * (u(rng) + 1), ww = u(rng), len = 0.5 + u(rng) * 0.4;
        const TPoint2D q(u(rng) * 1.5, u(rng) * 1.5);
        double best = 1e300;
        for (int k = 0; k <= 20000; k++) {
            const double s = len * k / 20000;
            double x = s, y = 0;
            if (std::abs(ww) > 1e-9) {
                const double rr = vv / ww;
                x = rr * std::sin(s / rr), y = rr * (1 - std::cos(s / rr));
            }
            best = std::min(best, std::hypot(q.x - x, q.y - y));
        }
        // poses 2 cm apart: within 1 cm of the continuous least
        EXPECT_NEAR(arcClearance({q}, vv, ww, len), best, 0.0101) << "case " << t;
    }
}

TEST(PlanFollow, TurnsToAnAimBehindThenDrivesAlong) {
    const auto plan = straightPlan(0, 0, 5, 0);
    // facing away from the plan: a turn in place, no translation
    auto c = planFollowCommand(TPose2D(0, 0, M_PI), plan, {}, 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "turn");
    EXPECT_EQ(c.v, 0);
    EXPECT_NEAR(std::abs(c.w), 0.5, 1e-12);
    // aligned: straight on at full speed
    c = planFollowCommand(TPose2D(0, 0, 0), plan, {}, 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "drive");
    EXPECT_NEAR(c.v, 0.2, 1e-12);
    EXPECT_NEAR(c.w, 0, 1e-12);
    // beside the plan (0.1 m to its right, heading along): bends left to it
    c = planFollowCommand(TPose2D(0, -0.1, 0), plan, {}, 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "drive");
    EXPECT_GT(c.w, 0);
    EXPECT_LT(c.v, 0.2);
}

TEST(PlanFollow, PassesAGapItsShapeFitsAndStopsAtAWall) {
    const auto plan = straightPlan(0, 0, 5, 0);
    // two posts 0.66 m apart 0.6 m ahead (a shape of 0.33 m fits; 0.28 m
    // asked): driven through
    std::vector<TPoint2D> posts;
    for (double x = 0.5; x <= 0.7; x += 0.02)
        posts.emplace_back(x, 0.33), posts.emplace_back(x, -0.33);
    auto c = planFollowCommand(TPose2D(0, 0, 0), plan, posts, 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "drive");
    EXPECT_GT(c.v, 0);
    // a wall across the way 0.3 m ahead: even vMax / 8 for the horizon
    // (2.5 cm + 5 cm) comes within 0.28 m of it
    std::vector<TPoint2D> wall;
    for (double y = -1; y <= 1; y += 0.02)
        wall.emplace_back(0.3, y);
    c = planFollowCommand(TPose2D(0, 0, 0), plan, wall, 0.28, 0.2, 0.5);
    EXPECT_TRUE(c.blocked);
    EXPECT_EQ(c.v, 0);
    EXPECT_EQ(c.w, 0);
    // the same wall farther: slowed, not blocked (0.2 m/s for 1 s + 5 cm
    // reaches 0.25 m: 0.6 - 0.25 = 0.35 >= 0.28)
    for (auto& q : wall)
        q.x = 0.6;
    c = planFollowCommand(TPose2D(0, 0, 0), plan, wall, 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "drive");
    EXPECT_NEAR(c.v, 0.2, 1e-12);
    for (auto& q : wall)
        q.x = 0.5;  // 0.5 - 0.25 < 0.28: halved to 0.1 m/s (0.15 m: 0.35 left)
    c = planFollowCommand(TPose2D(0, 0, 0), plan, wall, 0.28, 0.2, 0.5);
    EXPECT_NEAR(c.v, 0.1, 1e-12);
}

TEST(PlanFollow, ARobotAlreadyNearAPostMayGoOnIfItGetsNoNearer) {
    // stopped 0.26 m from a post beside it (nearer than the 0.28 m asked):
    // driving along the plan moves away from it, so that is allowed
    const auto plan = straightPlan(0, 0, 5, 0);
    const std::vector<TPoint2D> post{TPoint2D(0, 0.26), TPoint2D(-0.05, 0.26)};
    auto c = planFollowCommand(TPose2D(0, 0, 0), plan, post, 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "drive");
    EXPECT_GT(c.v, 0);
    // a post ahead 0.26 m away: every arc nears it, blocked
    c = planFollowCommand(TPose2D(0, 0, 0), plan, {TPoint2D(0.26, 0)}, 0.28, 0.2, 0.5);
    EXPECT_TRUE(c.blocked);
}

TEST(PlanFollow, AHeadingPastAPostIsTurnedOutOfBeforeDriving) {
    // the plan runs along y = 0 past a post at (0.2, 0.33); the robot, 8 cm
    // beside the plan, faces 18 deg left (27 deg off the aim), toward the post: every arc
    // from that heading nears it within 0.28 m, so it turns right in place first; facing
    // the aim, it drives
    const auto plan = straightPlan(0, 0, 5, 0);
    const std::vector<TPoint2D> post{TPoint2D(0.2, 0.33)};
    const TPose2D facingPost(0, 0.08, 18 * M_PI / 180);
    auto c =
        planFollowCommand(facingPost, plan, robotFrame(facingPost, post), 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "turn");
    EXPECT_LT(c.w, 0);
    const TPose2D facingAim(0, 0.08, std::atan2(-0.08, 0.5));
    c = planFollowCommand(facingAim, plan, robotFrame(facingAim, post), 0.28, 0.2, 0.5);
    EXPECT_EQ(c.what, "drive");
    EXPECT_GT(c.v, 0);
}

TEST(PlanFollow, NoPlanOrNoSpeedIsBlocked) {
    EXPECT_TRUE(planFollowCommand(TPose2D(0, 0, 0), {}, {}, 0.28, 0.2, 0.5).blocked);
    EXPECT_TRUE(
        planFollowCommand(TPose2D(0, 0, 0), straightPlan(0, 0, 1, 0), {}, 0.28, 0, 0.5)
            .blocked);
}

TEST(PlanFollow, ARobotWithinItsBodyFloorGetsNoNearerAtAll) {
    // straight ahead along the plan, a post 0.255 m beside the way 5 cm on:
    // the robot stands 0.260 m from it. Without a floor the 5 mm allowed
    // for the scan's noise lets it drive past at 0.255 m, and cycle after
    // cycle onto the post; with the body's floor (0.27 m) it gets no nearer
    const auto plan = straightPlan(0, 0, 5, 0);
    const std::vector<TPoint2D> post{TPoint2D(0.05, 0.255)};
    const TPose2D at(0, 0, 0);
    EXPECT_EQ(planFollowCommand(at, plan, post, 0.28, 0.2, 0.5).what, "drive");
    EXPECT_TRUE(
        planFollowCommand(at, plan, post, 0.28, 0.2, 0.5, 0.5, 1.0, 0.27).blocked);
    // a post beside the robot it leaves behind: it may drive away
    const std::vector<TPoint2D> beside{TPoint2D(-0.05, 0.255)};
    EXPECT_EQ(planFollowCommand(at, plan, beside, 0.28, 0.2, 0.5, 0.5, 1.0, 0.27).what,
              "drive");
    // from 0.2726 m (above the floor) to 0.268 m: below the floor, blocked
    const std::vector<TPoint2D> ahead{TPoint2D(0.05, 0.268)};
    EXPECT_EQ(planFollowCommand(at, plan, ahead, 0.28, 0.2, 0.5).what, "drive");
    EXPECT_TRUE(
        planFollowCommand(at, plan, ahead, 0.28, 0.2, 0.5, 0.5, 1.0, 0.27).blocked);
}
