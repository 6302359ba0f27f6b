#include <risknav/common/TOdometryOptions.h>
#include <risknav/common/config_read.h>

#include <algorithm>

namespace risknav::common {
namespace {
const std::vector<std::string> kModels = {"systematic", "per_step", "none"};
}

void TOdometryOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                          const std::string& s) {
    wheel_radius_l = readDouble(c, s, "wheel_radius_l", wheel_radius_l);
    wheel_radius_r = readDouble(c, s, "wheel_radius_r", wheel_radius_r);
    tread = readDouble(c, s, "tread", tread);
    sigma_wheel_radius_l = readDouble(c, s, "sigma_wheel_radius_l", sigma_wheel_radius_l);
    sigma_wheel_radius_r = readDouble(c, s, "sigma_wheel_radius_r", sigma_wheel_radius_r);
    sigma_tread = readDouble(c, s, "sigma_tread", sigma_tread);
    error_model = readChoice(c, s, "error_model", error_model, kModels);
}

void TOdometryOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                        const std::string& s) const {
    writeKey(c, s, "wheel_radius_l", wheel_radius_l);
    writeKey(c, s, "wheel_radius_r", wheel_radius_r);
    writeKey(c, s, "tread", tread);
    writeKey(c, s, "sigma_wheel_radius_l", sigma_wheel_radius_l);
    writeKey(c, s, "sigma_wheel_radius_r", sigma_wheel_radius_r);
    writeKey(c, s, "sigma_tread", sigma_tread);
    writeKey(c, s, "error_model", error_model);
}

void TOdometryOptions::validate() const {
    const std::string s = "Odometry";
    checkKey(s, "wheel_radius_l", wheel_radius_l, TRange::closed(0.005, 2, "m"));
    checkKey(s, "wheel_radius_r", wheel_radius_r, TRange::closed(0.005, 2, "m"));
    checkKey(s, "tread", tread, TRange::closed(0.02, 5, "m"));
    checkKey(s, "sigma_wheel_radius_l", sigma_wheel_radius_l, TRange::nonNegative("m"));
    checkKey(s, "sigma_wheel_radius_r", sigma_wheel_radius_r, TRange::nonNegative("m"));
    checkKey(s, "sigma_tread", sigma_tread, TRange::nonNegative("m"));
    // A 3-sigma error must not flip the sign of a radius or of the tread.
    checkRule(3 * sigma_wheel_radius_l < wheel_radius_l, s, "sigma_wheel_radius_l",
              numberText(sigma_wheel_radius_l), "must be < wheel_radius_l / 3");
    checkRule(3 * sigma_wheel_radius_r < wheel_radius_r, s, "sigma_wheel_radius_r",
              numberText(sigma_wheel_radius_r), "must be < wheel_radius_r / 3");
    checkRule(3 * sigma_tread < tread, s, "sigma_tread", numberText(sigma_tread),
              "must be < tread / 3");
    checkRule(std::find(kModels.begin(), kModels.end(), error_model) != kModels.end(), s,
              "error_model", error_model, "must be one of: systematic, per_step, none");
}

}  // namespace risknav::common
