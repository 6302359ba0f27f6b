#include <risknav/sim/CDiffDriveVehicle.h>
#include <risknav/sim/odometry_model.h>

#include <cmath>

namespace risknav::sim {
void CDiffDriveVehicle::advance(double v, double w, double dt) {
    // MRPT's command bookkeeping (getV()/getW(), sendVelCmd() callers).
    movementCommand(v, w);
    setV(v);
    setW(w);
    m_GT_pose = integrateTwist(m_GT_pose, v, w, dt);
    m_odometry = integrateTwist(m_odometry, v, w, dt);
    // Global-frame twists at the new headings, as MRPT's step leaves them.
    m_GT_vel = {v * std::cos(m_GT_pose.phi), v * std::sin(m_GT_pose.phi), w};
    m_odometric_vel = {v * std::cos(m_odometry.phi), v * std::sin(m_odometry.phi), w};
    m_time += dt;
}

}  // namespace risknav::sim
