#include <risknav/common/TOdometryOptions.h>
#include <risknav/common/config_read.h>

namespace risknav::common {
void TOdometryOptions::declare(Visitor& v) {
    v.number(wheel_radius_l, "wheel_radius_l", TRange::closed(0.005, 2, "m"),
             "nominal radius of the left wheel");
    v.number(wheel_radius_r, "wheel_radius_r", TRange::closed(0.005, 2, "m"),
             "nominal radius of the right wheel");
    v.number(tread, "tread", TRange::closed(0.02, 5, "m"), "nominal wheel separation");
    v.number(sigma_wheel_radius_l, "sigma_wheel_radius_l", TRange::nonNegative("m"),
             "std. dev. of the left wheel's true radius (< wheel_radius_l / 3)");
    v.number(sigma_wheel_radius_r, "sigma_wheel_radius_r", TRange::nonNegative("m"),
             "std. dev. of the right wheel's true radius (< wheel_radius_r / 3)");
    v.number(sigma_tread, "sigma_tread", TRange::nonNegative("m"),
             "std. dev. of the true tread (< tread / 3)");
    v.choice(error_model, "error_model", {"systematic", "per_step", "none"},
             "errors drawn once per run, every step, or none");
}

void TOdometryOptions::validateRules() const {
    const std::string& s = section;
    checkRule(3 * sigma_wheel_radius_l < wheel_radius_l, s, "sigma_wheel_radius_l",
              numberText(sigma_wheel_radius_l), "must be < wheel_radius_l / 3");
    checkRule(3 * sigma_wheel_radius_r < wheel_radius_r, s, "sigma_wheel_radius_r",
              numberText(sigma_wheel_radius_r), "must be < wheel_radius_r / 3");
    checkRule(3 * sigma_tread < tread, s, "sigma_tread", numberText(sigma_tread),
              "must be < tread / 3");
}

}  // namespace risknav::common
