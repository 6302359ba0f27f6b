#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/scan_points.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::sim {
IMPLEMENTS_MRPT_OBJECT(CStoppingDistanceLimiter, risknav::common::CSpeedLimiter,
                       risknav::sim)

void CStoppingDistanceLimiter::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s) {
    enabled = readBool(c, s, "enabled", enabled);
    margin = readDouble(c, s, "margin", margin);
    lateral_margin = readDouble(c, s, "lateral_margin", lateral_margin);
}

void CStoppingDistanceLimiter::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const {
    writeKey(c, s, "enabled", enabled);
    writeKey(c, s, "margin", margin);
    writeKey(c, s, "lateral_margin", lateral_margin);
}

void CStoppingDistanceLimiter::TOptions::validate() const {
    checkKey("StoppingRule", "margin", margin, TRange::closed(0, 10, "m"));
    checkKey("StoppingRule", "lateral_margin", lateral_margin, TRange::closed(0, 2, "m"));
}

void CStoppingDistanceLimiter::loadConfig(const mrpt::config::CConfigFileBase& c,
                                          const std::string& section) {
    loadOptions(options, c, section);
}

void CStoppingDistanceLimiter::saveConfig(mrpt::config::CConfigFileBase& c,
                                          const std::string& section) const {
    options.saveToConfigFile(c, section);
}

bool CStoppingDistanceLimiter::blocked(const mrpt::obs::CObservation2DRangeScan& scan,
                                       double v, const TRobotOptions& robot) const {
    return blocked(mapping::scanToRobotFrame(scan), v, robot);
}

bool CStoppingDistanceLimiter::blocked(const std::vector<mrpt::math::TPoint2D>& pts,
                                       double v, const TRobotOptions& robot) const {
    if (!options.enabled || v <= 0)
        return false;
    const double reach = stoppingDistance(v, robot.t_delay, robot.decel) + options.margin;
    const double halfW = robot.radius + options.lateral_margin;
    for (const auto& p : pts)
        if (p.x > 0 && std::abs(p.y) <= halfW && p.x - robot.radius < reach)
            return true;
    return false;
}

TSpeedLimit CStoppingDistanceLimiter::impl_limit(const TSpeedLimitInput& in) const {
    bool stop = in.scan && blocked(*in.scan, in.desiredSpeed, *in.robot);
    if (!stop && in.obstacles) {
        std::vector<mrpt::math::TPoint2D> pts;
        const auto& xs = in.obstacles->getPointsBufferRef_x();
        const auto& ys = in.obstacles->getPointsBufferRef_y();
        for (size_t i = 0; i < xs.size(); i++)
            pts.push_back({double(xs[i]), double(ys[i])});
        stop = blocked(pts, in.desiredSpeed, *in.robot);
    }
    if (stop)
        return {0.0, "obstacle within the stopping distance"};
    return {in.desiredSpeed, ""};
}

void registerAllClasses_sim() {
    common::registerAllClasses_common();
    mrpt::rtti::registerClass(CLASS_ID(CStoppingDistanceLimiter));
}

}  // namespace risknav::sim
