#pragma once
#include <risknav/common/diff_drive.h>

#include <Eigen/Dense>

namespace risknav::risk {
/** Differential-drive odometry model of Irie, Nagatani, Gofuku (001), section 4. */
struct TOdometryModel {
    double radiusL = 0.063, radiusR = 0.063,
           tread = 0.399;  ///< nominal m = [R_l R_r T] [m]
    double sigmaRL = 0.001, sigmaRR = 0.001,
           sigmaT = 0.001;  ///< std. dev. of m [m], eq. (25)
    /** Process noise n of eq. (3): P += tau n, covariance Sigma_n [(m/s)^2, (rad/s)^2].
     */
    Eigen::Matrix3d sigmaN = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d sigmaM() const;  ///< eq. (25)
    common::TWheelGeometry geometry() const { return {radiusL, radiusR, tread}; }
};

/** How the wheel-parameter error acts.
 *  - PerStep: a fresh error every step (the paper's eq. 15; the result depends on tau).
 *  - Systematic: the radii and tread are wrong by a constant (unknown) amount for
 *    the whole run: the error is propagated as part of an augmented state
 *    [x y theta R_l R_r T]. This is the physically right model and our default;
 *    going beyond the paper (PAPER_NOTES M2 "Note"). */
enum class TErrorModel { PerStep, Systematic };

/** Body twist from wheel speeds, eqs. (18)-(19), with the nominal m. */
inline void twistFromWheels(const TOdometryModel& m, double uL, double uR, double& v,
                            double& w) {
    common::twistFromWheels(m.geometry(), uL, uR, v, w);
}
/** Wheel speeds for a body twist (inverse of eqs. 18-19, nominal m). */
inline void wheelsFromTwist(const TOdometryModel& m, double v, double w, double& uL,
                            double& uR) {
    common::wheelsFromTwist(m.geometry(), v, w, uL, uR);
}

/** J_P = d f / d P, the 3x3 Jacobian of eq. (10) (PAPER_NOTES erratum: the paper
 * calls it j[t] but names the Jacobians the other way round in (8)-(9)):
 *   [[1, 0, -tau v sin th], [0, 1, tau v cos th], [0, 0, 1]]. */
Eigen::Matrix3d jacobianPose(double theta, double v, double tau);
/** J_V = d f / d V, eq. (11): [[tau cos th, 0], [tau sin th, 0], [0, tau]]. */
Eigen::Matrix<double, 3, 2> jacobianVelocity(double theta, double tau);
/** L = d(v, omega) / d(R_l, R_r, T), eq. (27) with the PAPER_NOTES erratum
 * (last entry -(R_r u_r - R_l u_l) / T^2; the paper prints R_r u_l):
 *   [[u_l/2, u_r/2, 0], [-u_l/T, u_r/T, -(R_r u_r - R_l u_l)/T^2]]. */
Eigen::Matrix<double, 2, 3> jacobianWheelParams(const TOdometryModel& m, double uL,
                                                double uR);

/** One step of eq. (15): Sigma_P' = J_P Sigma_P J_P^T + J_V Sigma_V J_V^T + tau^2
 * Sigma_n, Sigma_V = L Sigma_m L^T (eq. 23). `theta` is the heading at the start of the
 * step. */
Eigen::Matrix3d propagatePerStep(const Eigen::Matrix3d& sigmaP, double theta, double uL,
                                 double uR, double tau, const TOdometryModel& m);

/** One step of the systematic model on the augmented covariance (6x6, order
 * x y theta R_l R_r T): z' = F z with F = [[J_P, J_V L], [0, I]], plus
 * tau^2 Sigma_n on the pose block. */
Eigen::Matrix<double, 6, 6> propagateSystematic(const Eigen::Matrix<double, 6, 6>& sigmaZ,
                                                double theta, double uL, double uR,
                                                double tau, const TOdometryModel& m);

/** Initial augmented covariance: blockdiag(Sigma_P0, Sigma_m). */
Eigen::Matrix<double, 6, 6> augmentedInitial(const Eigen::Matrix3d& sigmaP0,
                                             const TOdometryModel& m);

}  // namespace risknav::risk
