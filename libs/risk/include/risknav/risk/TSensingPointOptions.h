#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/risk/path_risk.h>

#include <cmath>
#include <limits>
#include <string>

namespace risknav::risk {
/** A sensing point (landmark / ceiling observation place, Irie et al. section
 * 5.1 / 6.4): one [SensingPointN] section. Passing within `radius` resets the
 * pose covariance to the sigmas given. Every key is declared once, in
 * declare(). */
struct TSensingPointOptions : public common::CDeclaredOptions {
    TSensingPointOptions() { section = "SensingPoint1"; }
    std::string name;                                     ///< default: the section name
    double x = std::numeric_limits<double>::quiet_NaN();  ///< [m] required
    double y = std::numeric_limits<double>::quiet_NaN();  ///< [m] required
    double radius = 0.1;                                  ///< [m]
    double sigma_x = 0.001;                               ///< [m] after sensing
    double sigma_y = 0.001;                               ///< [m]
    double sigma_theta_deg = 0.1 * 180.0 / M_PI;          ///< [deg]

    /** The point for evaluatePathRisk(): resetCov = diag(sigma_x^2, sigma_y^2,
     * sigma_theta^2) [m^2, m^2, rad^2]. */
    TSensingPoint point() const;

  protected:
    void declare(Visitor& v) override;
    void onLoaded() override;
};

}  // namespace risknav::risk
