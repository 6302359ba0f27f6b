#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/diff_drive.h>

#include <string>

namespace risknav::common {
/** Wheel odometry of a differential-drive robot, the same [Odometry] keys in
 * every app: nominal wheel radii and tread, the standard deviations of their
 * errors, and how the errors behave (Irie et al. (001) section 4; PAPER_NOTES
 * M2): `systematic` (drawn once: constant biases of a real robot, the
 * default), `per_step` (fresh every step: the paper's eq. 15) or `none`.
 * Apps may read further keys of their own from the same section. Every key,
 * its range and its doc are declared once, in declare(). */
struct TOdometryOptions : public CDeclaredOptions {
    TOdometryOptions() { section = "Odometry"; }
    double wheel_radius_l = 0.063;           ///< [m] nominal
    double wheel_radius_r = 0.063;           ///< [m] nominal
    double tread = 0.399;                    ///< [m] nominal wheel separation
    double sigma_wheel_radius_l = 0.001;     ///< [m] std. dev. of the left radius
    double sigma_wheel_radius_r = 0.001;     ///< [m] std. dev. of the right radius
    double sigma_tread = 0.001;              ///< [m] std. dev. of the tread
    std::string error_model = "systematic";  ///< systematic | per_step | none

    TWheelGeometry nominal() const { return {wheel_radius_l, wheel_radius_r, tread}; }

  protected:
    void declare(Visitor& v) override;
    /** A 3-sigma error must not flip the sign of a radius or of the tread. */
    void validateRules() const override;
};

}  // namespace risknav::common
