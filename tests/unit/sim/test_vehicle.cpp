// The robot drives the commanded motion for exactly the time stepped, at
// every physics step the apps accept (sim_dt in [0.001, 0.5] s): through the
// world (risknav-simulate, -explore) and MRPT's robot interface on it
// (risknav-navigate).
#include <risknav/sim/CDiffDriveVehicle.h>
#include <risknav/sim/CSimRobotInterface.h>
#include <risknav/sim/CSimWorld.h>

#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::sim;
using mrpt::math::TPose2D;

namespace {
const double kDts[] = {0.001, 0.002, 0.005, 0.01, 0.05, 0.1, 0.2, 0.5};

mrpt::maps::COccupancyGridMap2D emptyRoom() {
    mrpt::maps::COccupancyGridMap2D g(-10, 30, -10, 10, 0.05f);
    g.fill(1.0f);
    return g;
}
}  // namespace

TEST(DiffDriveVehicle, StepsExactlyTheTimeAsked) {
    for (const double dt : kDts) {
        CDiffDriveVehicle veh;
        const int n = int(std::lround(10.0 / dt));
        for (int i = 0; i < n; i++)
            veh.advance(0.2, 0, dt);
        // MRPT's simulateOneTimeStep(dt) gave 2.40 m at 1 ms, 2.11 m at 5 ms,
        // 2.01 m at 50 ms (its clock as far ahead).
        EXPECT_NEAR(veh.getCurrentGTPose().x, 2.0, 1e-9) << "dt " << dt;
        EXPECT_NEAR(veh.getCurrentGTPose().y, 0.0, 1e-12) << "dt " << dt;
        EXPECT_NEAR(veh.getTime(), 10.0, 1e-9) << "dt " << dt;
        EXPECT_NEAR(veh.getCurrentOdometricPose().x, 2.0, 1e-9) << "dt " << dt;
        EXPECT_NEAR(veh.getCurrentGTVel().vx, 0.2, 1e-12);
    }
}

TEST(DiffDriveVehicle, TurnsOnTheExactArc) {
    for (const double dt : kDts) {
        CDiffDriveVehicle veh;
        veh.setCurrentGTPose(TPose2D(1, 2, 0.3));
        const double v = 0.5, w = 0.25, T = 4.0, R = v / w;
        const int n = int(std::lround(T / dt));
        for (int i = 0; i < n; i++)
            veh.advance(v, w, dt);
        const auto p = veh.getCurrentGTPose();
        EXPECT_NEAR(p.phi, 0.3 + w * T, 1e-9) << "dt " << dt;
        // The circle of radius v / w through the start, tangent to its heading.
        EXPECT_NEAR(p.x, 1 + R * (std::sin(0.3 + w * T) - std::sin(0.3)), 1e-9);
        EXPECT_NEAR(p.y, 2 - R * (std::cos(0.3 + w * T) - std::cos(0.3)), 1e-9);
    }
}

// A straight leg at a constant speed, once the robot is up to speed: the
// world's distance over T equals v T and its clock T, at every sim_dt.
TEST(SimWorld, StraightLegIsSpeedTimesTimeAtEverySimDt) {
    for (const double dt : kDts) {
        CSimWorld w;
        w.odometry.options.error_model = "none";
        w.setMap(emptyRoom());
        w.reset(TPose2D(0, 0, 0), 1);
        const double v = 0.2;
        for (int i = 0, n = int(std::lround(1.0 / dt)); i < n; i++)  // up to speed
            w.step(v, 0, dt);
        ASSERT_NEAR(w.speed(), v, 1e-12);
        const TPose2D p0 = w.truePose();
        const double t0 = w.time();
        for (int i = 0, n = int(std::lround(20.0 / dt)); i < n; i++)
            w.step(v, 0, dt);
        EXPECT_NEAR(w.truePose().x - p0.x, v * 20.0, 1e-9) << "sim_dt " << dt;
        EXPECT_NEAR(w.time() - t0, 20.0, 1e-9) << "sim_dt " << dt;
        EXPECT_NEAR(std::hypot(w.velocity().vx, w.velocity().vy), v, 1e-12);
    }
}

// risknav-navigate's way: MRPT's navigator commands through the robot
// interface (max_v 1.1 m/s was driven at 1.5 m/s with sim_dt = 0.001), reads
// the pose and speed back from it and times itself on the vehicle's clock.
TEST(SimRobotInterface, NavigatorCommandIsDrivenAtEverySimDt) {
    for (const double dt : kDts) {
        CSimWorld w;
        w.robot.max_v = 1.1;
        w.robot.accel = w.robot.decel = 2.0;
        w.odometry.options.error_model = "none";
        w.setMap(emptyRoom());
        w.reset(TPose2D(0, 0, 0), 1);
        CSimRobotInterface robot(w);
        robot.resetNavigationTimer();
        mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
        cmd.lin_vel = 5.0;  // beyond max_v: clamped
        cmd.ang_vel = 0;
        ASSERT_TRUE(robot.changeSpeeds(cmd));
        double maxSpeed = 0;
        TPose2D prev = w.truePose();
        for (int i = 0, n = int(std::lround(10.0 / dt)); i < n; i++) {
            w.step(dt);
            const TPose2D p = w.truePose();
            maxSpeed = std::max(maxSpeed, std::hypot(p.x - prev.x, p.y - prev.y) / dt);
            prev = p;
        }
        mrpt::math::TPose2D pose, odo;
        mrpt::math::TTwist2D vel;
        mrpt::system::TTimeStamp ts;
        std::string frame;
        ASSERT_TRUE(robot.getCurrentPoseAndSpeeds(pose, vel, ts, odo, frame));
        // 0.55 s up to 1.1 m/s at 2 m/s^2 (0.3025 m), then 9.45 s at 1.1 m/s;
        // the speed ramps in sim_dt steps, each driven for its whole step.
        double expect = 0, vv = 0;
        for (int i = 0, n = int(std::lround(10.0 / dt)); i < n; i++) {
            vv = std::min(1.1, vv + 2.0 * dt);
            expect += vv * dt;
        }
        EXPECT_NEAR(pose.x, expect, 1e-9) << "sim_dt " << dt;
        EXPECT_NEAR(odo.x, expect, 1e-9) << "sim_dt " << dt;
        EXPECT_LE(maxSpeed, 1.1 + 1e-9) << "sim_dt " << dt;
        EXPECT_NEAR(vel.vx, 1.1, 1e-12);
        EXPECT_NEAR(robot.getNavigationTime(), 10.0, 1e-9) << "sim_dt " << dt;
    }
}
