#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/TOdometryOptions.h>
#include <risknav/risk/path_risk.h>

#include <cmath>
#include <cstdint>
#include <string>

namespace risknav::risk {
/** How the risk evaluator drives a route and propagates its covariance: the
 * risk-only keys of [Odometry] (the wheel geometry, its sigmas and the error
 * model are common::TOdometryOptions, in the same section). Degrees in the
 * file and here, radians in TRiskOptions. Every key is declared once, in
 * declare(). */
struct TPropagationOptions : public common::CDeclaredOptions {
    TPropagationOptions() { section = "Odometry"; }  // the host section

    double tau = 0.05;          ///< [s] propagation step of eq. (15)
    double speed = 0.3;         ///< [m/s] on straight legs
    double turn_rate_deg = 30;  ///< [deg/s] turns in place at waypoints
    /** Initial pose standard deviations (Irie et al. section 6.2: 1 mm, 1 mm,
     * 0.1 rad). */
    double init_sigma_x = 0.001;                       ///< [m]
    double init_sigma_y = 0.001;                       ///< [m]
    double init_sigma_theta_deg = 0.1 * 180.0 / M_PI;  ///< [deg]
    /** Process noise n of eq. (3), standard deviations per axis. */
    double noise_sigma_x = 0;          ///< [m/s]
    double noise_sigma_y = 0;          ///< [m/s]
    double noise_sigma_theta_deg = 0;  ///< [deg/s]
    /** linear | unscented | cubature5 | sampled (TPropagation). The default,
     * cubature5, by measurement: on the paper's Fig. 2 path its covariance is
     * within 1-2 % of a Monte Carlo of the same model for both error models,
     * where linear is off by up to 2.2x (systematic) and unscented by 20 %
     * (the ratio table: tests/unit/risk/test_covariance.cpp). */
    std::string propagation = "cubature5";
    int samples = 1000;  ///< draws of `sampled`

  protected:
    void declare(Visitor& v) override;
};

/** The numbers evaluatePathRisk() takes, from the odometry and propagation
 * options, the sampling step [m] and the seed of `sampled`. error_model `none`
 * (exact wheels) keeps only the initial pose error and the process noise: the
 * wheel sigmas are taken as 0 (Sigma_m = 0 in eq. 25) with the per-step model. */
TRiskOptions makeRiskOptions(const common::TOdometryOptions& odometry,
                             const TPropagationOptions& propagation, double evalStep,
                             uint64_t seed = 1);

/** The propagation named by a [Odometry] propagation word (validated). */
TPropagation propagationFromName(const std::string& name);

}  // namespace risknav::risk
