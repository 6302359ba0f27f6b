#include <risknav/common/config_read.h>
#include <risknav/mapping/TObstacleRule.h>

using namespace risknav::common;

namespace risknav::mapping {
void TObstacleRule::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                       const std::string& s) {
    section = s;
    occupied_threshold = readDouble(c, s, "occupied_threshold", occupied_threshold);
    free_threshold = readDouble(c, s, "free_threshold", free_threshold);
    unknown_is_obstacle = readBool(c, s, "unknown_is_obstacle", unknown_is_obstacle);
    outside_is_obstacle = readBool(c, s, "outside_is_obstacle", outside_is_obstacle);
}

void TObstacleRule::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                     const std::string& s) const {
    writeKey(c, s, "occupied_threshold", occupied_threshold);
    writeKey(c, s, "free_threshold", free_threshold);
    writeKey(c, s, "unknown_is_obstacle", unknown_is_obstacle);
    writeKey(c, s, "outside_is_obstacle", outside_is_obstacle);
}

void TObstacleRule::validate() const {
    checkKey(section, "occupied_threshold", occupied_threshold, TRange::closed(0.01, 1));
    checkKey(section, "free_threshold", free_threshold, TRange::closed(0, 0.99));
    checkRule(free_threshold < occupied_threshold, section, "free_threshold",
              numberText(free_threshold), "must be < occupied_threshold");
}

}  // namespace risknav::mapping
