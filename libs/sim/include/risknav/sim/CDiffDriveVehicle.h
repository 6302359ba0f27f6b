#pragma once
#include <mrpt/kinematics/CVehicleSimul_DiffDriven.h>

namespace risknav::sim {
/** MRPT's differential-drive vehicle simulator, stepped for exactly the
 * time asked.
 *
 * MRPT 2.5.8's CVehicleSimulVirtualBase::simulateOneTimeStep(dt) loops
 * `while (m_time <= m_time0 + dt)` over its 0.5 ms firmware period, so every
 * call integrates one period more than dt (often): +50 % of motion at
 * dt = 1 ms, +10 % at 5 ms, +1 % at 50 ms, and the vehicle's clock
 * (getTime(), the navigator's getNavigationTime()) runs as fast. advance()
 * replaces that loop, and only it: with MRPT's default delay model (no
 * delay, no low-pass, the one the world uses: it applies its own
 * acceleration limits before commanding) MRPT's model is "the twist is the
 * command", whose exact motion over dt is the constant-twist arc that MRPT's
 * Euler sub-steps approximate. The state MRPT's getters and
 * CRobot2NavInterfaceForSimulator_DiffDriven read (pose, velocity, ideal
 * odometry, time) is kept as MRPT keeps it. */
class CDiffDriveVehicle : public mrpt::kinematics::CVehicleSimul_DiffDriven {
  public:
    /** Drives the twist (v [m/s], w [rad/s]) for exactly dt [s] along its arc. */
    void advance(double v, double w, double dt);
};

}  // namespace risknav::sim
