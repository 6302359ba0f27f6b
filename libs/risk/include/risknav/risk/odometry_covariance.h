#pragma once
#include <risknav/common/diff_drive.h>

#include <Eigen/Dense>

#include <cstdint>
#include <vector>

namespace risknav::risk {
/** Differential-drive odometry model of Irie, Nagatani, Gofuku (001), section 4. */
struct TOdometryModel {
    double radiusL = 0.063, radiusR = 0.063,
           tread = 0.399;  ///< nominal m = [R_l R_r T] [m]
    double sigmaRL = 0.001, sigmaRR = 0.001,
           sigmaT = 0.001;  ///< std. dev. of m [m], eq. (25)
    /** Sigma_n = E(n n^T), eq. (17): the covariance of the process noise n of
     * eq. (3), P += tau n [(m/s)^2, (rad/s)^2]. */
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
/** J_V = d f / d V, eq. (11): [[tau cos th, 0], [tau sin th, 0], [0, tau]], the
 * true derivative of f = P + tau (v cos th, v sin th, omega). The paper prints
 * tau v cos th, tau v sin th in the first column (an erratum PAPER_NOTES does
 * not list; docs/EQUATIONS.md): those are not the derivative, nor in the right
 * units. */
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
 * tau^2 Sigma_n on the pose block. Replaces eqs. (15) and (23) of the default
 * `systematic` model: the wheel-parameter error Delta m of eq. (21) is a
 * constant of the run, carried in the state instead of drawn afresh. */
Eigen::Matrix<double, 6, 6> propagateSystematic(const Eigen::Matrix<double, 6, 6>& sigmaZ,
                                                double theta, double uL, double uR,
                                                double tau, const TOdometryModel& m);

/** Initial augmented covariance of the systematic model (state [P, Delta m],
 * Delta m of eq. 21): blockdiag(Sigma_P0, Sigma_m), Sigma_m of eq. (25). */
Eigen::Matrix<double, 6, 6> augmentedInitial(const Eigen::Matrix3d& sigmaP0,
                                             const TOdometryModel& m);

/** How the pose error is propagated along a route ([Odometry] propagation).
 *  - Linear: first order, the paper's eq. (15) (per_step) or its augmented
 *    form (systematic): exact for small errors, far off when the heading
 *    error bends the path (sin/cos saturate).
 *  - Unscented, Cubature5, Sampled: the random variables that are constant
 *    over a run (the initial pose error, and under `systematic` the wheel
 *    biases Delta m of eq. 21) are represented by points (sigma points of a
 *    cubature rule, or random draws), each driven along the route through the
 *    exact non-linear odometry of eqs. (3), (18), (19); the per-step errors
 *    (per_step wheel errors, process noise n) are small and stay linear
 *    (eq. 15) along each point's own trajectory. The pose covariance is the
 *    points' weighted spread plus their weighted conditional covariances.
 *    Unscented: 2n points at +-sqrt(n) sigma (third degree, kappa = 0);
 *    Cubature5: 2n^2 + 1 points, exact for polynomials of degree 5 (Jia, Xin,
 *    Cheng 2013, "High-degree cubature Kalman filter", Automatica 49(2));
 *    Sampled: a seeded Monte Carlo of TRiskOptions::samples draws. */
enum class TPropagation { Linear, Unscented, Cubature5, Sampled };

/** Points and weights of a rule that integrates over the standard normal
 * distribution N(0, I_n): E[g(xi)] ~ sum_j w_j g(xi_j). */
struct TSigmaPoints {
    std::vector<Eigen::VectorXd> points;
    std::vector<double> weights;
};
/** 2n points +-sqrt(n) e_i, weights 1/(2n): the unscented transform with
 * kappa = 0 (Julier & Uhlmann 2004; the third-degree spherical-radial cubature
 * rule), exact for polynomials of degree 3. */
TSigmaPoints unscentedPoints(int n);
/** The fifth-degree rule of Jia, Xin, Cheng (2013): the origin (weight
 * 2/(n+2)), +-sqrt(n+2) e_i (weight (4-n)/(2(n+2)^2), negative for n > 4)
 * and sqrt((n+2)/2) (+-e_i +-e_j), i < j (weight 1/(n+2)^2). */
TSigmaPoints cubature5Points(int n);
/** `count` draws of N(0, I_n) (std::mt19937_64 seeded with `seed`), weights
 * 1/count. */
TSigmaPoints sampledPoints(int n, int count, uint64_t seed);

}  // namespace risknav::risk
