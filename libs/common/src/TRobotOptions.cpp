#include <risknav/common/TRobotOptions.h>
#include <risknav/common/config_read.h>

namespace risknav::common {
void TRobotOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                       const std::string& s) {
    radius = readDouble(c, s, "radius", radius);
    max_v = readDouble(c, s, "max_v", max_v);
    max_w_deg = readDouble(c, s, "max_w_deg", max_w_deg);
    accel = readDouble(c, s, "accel", accel);
    decel = readDouble(c, s, "decel", decel);
    w_accel_deg = readDouble(c, s, "w_accel_deg", w_accel_deg);
    t_delay = readDouble(c, s, "t_delay", t_delay);
}

void TRobotOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                     const std::string& s) const {
    writeKey(c, s, "radius", radius);
    writeKey(c, s, "max_v", max_v);
    writeKey(c, s, "max_w_deg", max_w_deg);
    writeKey(c, s, "accel", accel);
    writeKey(c, s, "decel", decel);
    writeKey(c, s, "w_accel_deg", w_accel_deg);
    writeKey(c, s, "t_delay", t_delay);
}

void TRobotOptions::validate() const {
    const std::string s = "Robot";
    checkKey(s, "radius", radius, {0, 5, true, false, "m"});
    checkKey(s, "max_v", max_v, {0, 5, true, false, "m/s"});
    checkKey(s, "max_w_deg", max_w_deg, {0, 720, true, false, "deg/s"});
    checkKey(s, "accel", accel, {0, 20, true, false, "m/s^2"});
    checkKey(s, "decel", decel, {0, 20, true, false, "m/s^2"});
    checkKey(s, "w_accel_deg", w_accel_deg, {0, 10000, true, false, "deg/s^2"});
    checkKey(s, "t_delay", t_delay, TRange::closed(0, 10, "s"));
}

}  // namespace risknav::common
