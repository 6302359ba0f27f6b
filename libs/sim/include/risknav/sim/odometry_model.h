#pragma once
#include <mrpt/math/TPose2D.h>

namespace risknav::sim {
/** Wheel geometry of a differential-drive robot [m]. */
struct TWheelGeometry {
    double radiusL = 0.063, radiusR = 0.063, tread = 0.399;
};

/** Body twist from wheel angular speeds u [rad/s]; Irie et al. (001) eq. (5)-(6):
 *   v = (R_r u_r + R_l u_l) / 2,   omega = (R_r u_r - R_l u_l) / Tr */
void twistFromWheels(const TWheelGeometry& g, double uL, double uR, double& v, double& w);

/** Inverse of twistFromWheels: the wheel speeds that produce (v, omega). */
void wheelsFromTwist(const TWheelGeometry& g, double v, double w, double& uL, double& uR);

/** Pose after moving with constant (v, omega) for dt, on the exact arc
 * (straight line when omega = 0). Heading wrapped to (-pi, pi]. */
mrpt::math::TPose2D integrateTwist(const mrpt::math::TPose2D& p, double v, double w,
                                   double dt);

}  // namespace risknav::sim
