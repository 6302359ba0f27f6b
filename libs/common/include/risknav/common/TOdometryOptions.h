#pragma once
#include <risknav/common/CValidatedOptions.h>
#include <risknav/common/diff_drive.h>

#include <string>

namespace risknav::common {
/** Wheel odometry of a differential-drive robot, the same [Odometry] keys in
 * every app: nominal wheel radii and tread, the standard deviations of their
 * errors, and how the errors behave (Irie et al. (001) section 4; PAPER_NOTES
 * M2): `systematic` (drawn once: constant biases of a real robot, the
 * default), `per_step` (fresh every step: the paper's eq. 15) or `none`.
 * Apps may read further keys of their own from the same section. */
struct TOdometryOptions : public CValidatedOptions {
    double wheel_radius_l = 0.063;           ///< [m] nominal
    double wheel_radius_r = 0.063;           ///< [m] nominal
    double tread = 0.399;                    ///< [m] nominal wheel separation
    double sigma_wheel_radius_l = 0.001;     ///< [m] std. dev. of the left radius
    double sigma_wheel_radius_r = 0.001;     ///< [m] std. dev. of the right radius
    double sigma_tread = 0.001;              ///< [m] std. dev. of the tread
    std::string error_model = "systematic";  ///< systematic | per_step | none

    TWheelGeometry nominal() const { return {wheel_radius_l, wheel_radius_r, tread}; }

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                          const std::string& section) const override;
    void validate() const override;
};

}  // namespace risknav::common
