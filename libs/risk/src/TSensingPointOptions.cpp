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

void TSensingPointOptions::declare(Visitor& v) {
    v.text(name, "name", true, "unique; default: the section name");
    v.requiredNumber(x, "x", TRange::any("m (required)"),
                     "on the map, not in a (grown) obstacle");
    v.requiredNumber(y, "y", TRange::any("m (required)"), "the same");
    v.number(radius, "radius", TRange::closed(0.01, 10, "m"),
             "passing within this resets the pose covariance");
    // Bounded as [Odometry] init_sigma_*: no covariance can overflow (a
    // sensing point with sigma 1e308 would otherwise "help").
    v.number(sigma_x, "sigma_x", TRange::closed(0, 1000, "m"),
             "pose std. dev. after sensing, x");
    v.number(sigma_y, "sigma_y", TRange::closed(0, 1000, "m"), "the same, y");
    v.number(sigma_theta_deg, "sigma_theta_deg", TRange::closed(0, 180, "deg"),
             "the same, heading");
}

void TSensingPointOptions::onLoaded() {
    if (name.empty())
        name = section;
}

}  // namespace risknav::risk
