#pragma once
#include <risknav/risk/odometry_covariance.h>

#include <Eigen/Dense>

#include <cstdint>
#include <random>
#include <vector>

namespace risknav::risk {
/** The pose error of a differential-drive robot that executes planned wheel
 * speeds, step by step along a route (Irie et al. (001) section 4; PAPER_NOTES
 * M2), under either error model (TErrorModel) and any propagation
 * (TPropagation):
 *  - Linear: the covariance by eq. (15) (per_step) or the augmented
 *    F z F^T (systematic); the mean stays on the plan.
 *  - Unscented, Cubature5: each sigma point j is one robot whose constant
 *    random variables (initial pose error; with systematic also its wheel
 *    radii and tread) are fixed by the rule, driven through the non-linear
 *    odometry of eq. (3) with eqs. (18)-(19); its per-step errors (per_step
 *    wheel errors, process noise) are propagated by eq. (15) along its own
 *    trajectory (its heading in J_P, J_V) as a conditional covariance P_j.
 *    Then mean = sum_j w_j p_j, cov = sum_j w_j (P_j + (p_j - mean)(p_j -
 *    mean)^T) (p_j relative to the plan, headings wrapped). The per-step part
 *    stays first order: the along-track shortening L theta^2 / 2 by a
 *    heading error that per-step noise alone builds up is missed (it matters
 *    for the along-track entry only when nothing else spreads the robot).
 *  - Sampled: a Monte Carlo of the model: each sample draws its initial pose
 *    error and wheel biases once and, every step, fresh per_step wheel errors
 *    and process noise n (seeded): nothing is linearised.
 * The plan is the nominal pose the caller passes with each step (the robot's
 * commanded motion). */
class CPosePropagator {
  public:
    /** `sigmaP0`: initial pose covariance (x y theta) [m^2, rad^2], about the
     * planned start (x0, y0, theta0). `samples`, `seed`: Sampled only. */
    CPosePropagator(const TOdometryModel& m, TErrorModel model, TPropagation propagation,
                    const Eigen::Matrix3d& sigmaP0, double x0, double y0, double theta0,
                    int samples = 1000, uint64_t seed = 1);

    /** One step of tau seconds at the commanded wheel speeds uL, uR [rad/s],
     * starting at the planned heading thetaStart; the plan is at (x, y,
     * theta) at its end. */
    void step(double thetaStart, double uL, double uR, double tau, double x, double y,
              double theta);
    /** A landmark observation (a sensing point) fixes the pose error to
     * N(0, cov) about the plan, independently of the wheel biases (the
     * calibration uncertainty of the systematic model stays). */
    void reset(const Eigen::Matrix3d& cov);

    /** Covariance of the pose about its mean [m^2, m rad, rad^2]. */
    Eigen::Matrix3d covariance() const;
    /** mean - plan (x, y, theta): 0 for Linear. */
    Eigen::Vector3d bias() const;
    /** E[(p - plan)(p - plan)^T] = covariance + bias bias^T: the spread of the
     * robot about where it should be, what D_max measures (eq. 28 centred on
     * the path, as the paper). Equal to covariance() for Linear. */
    Eigen::Matrix3d secondMoment() const;
    /** Number of trajectories driven (1 for Linear). */
    size_t points() const { return m_linear ? 1 : m_pose.size(); }

  private:
    TOdometryModel m_m;
    TErrorModel m_model;
    bool m_linear;
    bool m_unbiased = false;   // Sampled: the spread with 1/(N-1)
    bool m_stepNoise = false;  // per-step errors to propagate linearly
    bool m_sampled = false;    // per-step errors drawn (Monte Carlo)
    Eigen::Vector3d m_plan;    // x y theta
    // Linear
    Eigen::Matrix3d m_p;              // per_step
    Eigen::Matrix<double, 6, 6> m_z;  // systematic
    // Points
    std::vector<Eigen::VectorXd> m_xi;  // in N(0, I_n), n = 3 or 6
    std::vector<double> m_w;
    std::vector<Eigen::Vector3d> m_pose, m_wheel;  // x y theta; R_l R_r T
    std::vector<Eigen::Matrix3d> m_cond;           // P_j
    std::mt19937_64 m_rng;                         // Sampled: per-step draws
    Eigen::Matrix3d m_noiseSqrt;                   // sqrt(Sigma_n)
    void placePoses(const Eigen::Matrix3d& cov);
};

}  // namespace risknav::risk
