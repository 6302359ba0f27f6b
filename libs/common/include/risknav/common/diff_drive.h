#pragma once

namespace risknav::common {
/** Wheel geometry of a differential-drive robot [m]. */
struct TWheelGeometry {
    double radiusL = 0.063, radiusR = 0.063, tread = 0.399;
};

/** Body twist from wheel angular speeds u [rad/s]; Irie et al. (001) eqs. (18)-(19):
 *   v = (R_r u_r + R_l u_l) / 2,   omega = (R_r u_r - R_l u_l) / Tr */
inline void twistFromWheels(const TWheelGeometry& g, double uL, double uR, double& v,
                            double& w) {
    v = 0.5 * (g.radiusR * uR + g.radiusL * uL);
    w = (g.radiusR * uR - g.radiusL * uL) / g.tread;
}

/** The wheel speeds that produce (v, omega): the inverse of twistFromWheels. */
inline void wheelsFromTwist(const TWheelGeometry& g, double v, double w, double& uL,
                            double& uR) {
    uR = (v + 0.5 * w * g.tread) / g.radiusR;
    uL = (v - 0.5 * w * g.tread) / g.radiusL;
}

}  // namespace risknav::common
