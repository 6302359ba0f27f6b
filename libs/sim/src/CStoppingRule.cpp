#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/scan_points.h>
#include <risknav/sim/CStoppingRule.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::sim {
void CStoppingRule::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                                 const std::string& s) {
    enabled = readBool(c, s, "enabled", enabled);
    margin = readDouble(c, s, "margin", margin);
    lateral_margin = readDouble(c, s, "lateral_margin", lateral_margin);
}

void CStoppingRule::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                               const std::string& s) const {
    writeKey(c, s, "enabled", enabled);
    writeKey(c, s, "margin", margin);
    writeKey(c, s, "lateral_margin", lateral_margin);
}

void CStoppingRule::TOptions::validate() const {
    checkKey("StoppingRule", "margin", margin, TRange::closed(0, 10, "m"));
    checkKey("StoppingRule", "lateral_margin", lateral_margin, TRange::closed(0, 2, "m"));
}

bool CStoppingRule::blocked(const mrpt::obs::CObservation2DRangeScan& scan, double v,
                            const TRobotOptions& robot) const {
    if (!options.enabled || v <= 0)
        return false;
    const double reach = stoppingDistance(v, robot.t_delay, robot.decel) + options.margin;
    const double halfW = robot.radius + options.lateral_margin;
    for (const auto& p : mapping::scanToRobotFrame(scan))
        if (p.x > 0 && std::abs(p.y) <= halfW && p.x - robot.radius < reach)
            return true;
    return false;
}

}  // namespace risknav::sim
