#include <risknav/sim/CRouteFollower.h>

#include <mrpt/kinematics/CVehicleSimul_DiffDriven.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::sim;

TEST(CRouteFollower, ExpandsLapsAndModes) {
    CRouteFollower r;
    r.options.waypoints = {0, 0, 1, 0, 2, 0};
    r.options.laps = 2;
    r.options.mode = "back_and_forth";
    r.reset();
    EXPECT_EQ(r.points().size(), 9u);  // A B C B A B C B A
    EXPECT_DOUBLE_EQ(r.length(), 8.0);
    r.options.mode = "loop";
    r.reset();
    EXPECT_EQ(r.points().size(), 7u);  // A B C A B C A
    r.options.mode = "once";
    r.options.laps = 1;
    r.options.speeds = {0.3, 0.6};
    r.reset();
    EXPECT_EQ(r.legSpeeds(), (std::vector<double>{0.0, 0.3, 0.6}));
}

TEST(CRouteFollower, DrivesAnLShapedRoute) {
    CRouteFollower r;
    r.options.waypoints = {0, 0, 4, 0, 4, 3};
    r.options.mode = "once";
    r.options.speed = 0.5;
    r.reset();
    mrpt::kinematics::CVehicleSimul_DiffDriven sim;
    sim.setCurrentGTPose(r.startPose());
    double maxDev = 0, t = 0;
    bool reachedCorner = false;
    while (!r.finished() && t < 60) {
        double v, w;
        r.compute(sim.getCurrentGTPose(), M_PI / 2, 1.0, v, w);
        sim.movementCommand(v, w);
        sim.simulateOneTimeStep(0.05);
        t += 0.05;
        const auto p = sim.getCurrentGTPose();
        // Distance to the L-shaped polyline.
        const double d1 = (p.x <= 4) ? std::abs(p.y) : std::hypot(p.x - 4, p.y);
        const double d2 = (p.y >= 0) ? std::abs(p.x - 4) : std::hypot(p.x - 4, p.y);
        maxDev = std::max(maxDev, std::min(d1, d2));
        reachedCorner |= std::hypot(p.x - 4, p.y) < r.options.goal_tolerance;
    }
    EXPECT_TRUE(r.finished());
    EXPECT_TRUE(reachedCorner);
    EXPECT_LT(maxDev, 0.15);
    EXPECT_LT(t, 7.0 / 0.5 + 8);  // 7 m at 0.5 m/s plus a turn in place and slow-downs
    const auto end = sim.getCurrentGTPose();
    EXPECT_LT(std::hypot(end.x - 4, end.y - 3), r.options.goal_tolerance);
}
