#include <risknav/common/config_read.h>
#include <risknav/risk/TSensingPointOptions.h>

using namespace risknav::common;

namespace risknav::risk {
TSensingPoint TSensingPointOptions::point() const {
    TSensingPoint p;
    p.name = name;
    p.x = x;
    p.y = y;
    p.radius = radius;
    const double t = sigma_theta_deg * M_PI / 180.0;
    p.resetCov =
        Eigen::Vector3d(sigma_x * sigma_x, sigma_y * sigma_y, t * t).asDiagonal();
    return p;
}

void TSensingPointOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                              const std::string& s) {
    section = s;
    name = readString(c, s, "name", s);
    x = requireDouble(c, s, "x", {});
    y = requireDouble(c, s, "y", {});
    radius = readDouble(c, s, "radius", radius);
    sigma_x = readDouble(c, s, "sigma_x", sigma_x);
    sigma_y = readDouble(c, s, "sigma_y", sigma_y);
    sigma_theta_deg = readDouble(c, s, "sigma_theta_deg", sigma_theta_deg);
}

void TSensingPointOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                            const std::string& s) const {
    writeKey(c, s, "name", name);
    writeKey(c, s, "x", x);
    writeKey(c, s, "y", y);
    writeKey(c, s, "radius", radius);
    writeKey(c, s, "sigma_x", sigma_x);
    writeKey(c, s, "sigma_y", sigma_y);
    writeKey(c, s, "sigma_theta_deg", sigma_theta_deg);
}

void TSensingPointOptions::validate() const {
    checkRule(!name.empty(), section, "name", name, "must not be empty");
    checkKey(section, "x", x, TRange::any("m (required)"));
    checkKey(section, "y", y, TRange::any("m (required)"));
    checkKey(section, "radius", radius, TRange::closed(0.01, 10, "m"));
    // Bounded as [Odometry] init_sigma_*: no covariance can overflow (a
    // sensing point with sigma 1e308 would otherwise "help").
    checkKey(section, "sigma_x", sigma_x, TRange::closed(0, 1000, "m"));
    checkKey(section, "sigma_y", sigma_y, TRange::closed(0, 1000, "m"));
    checkKey(section, "sigma_theta_deg", sigma_theta_deg, TRange::closed(0, 180, "deg"));
}

}  // namespace risknav::risk
