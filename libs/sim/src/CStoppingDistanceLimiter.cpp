#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/scan_points.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace risknav::common;

namespace risknav::sim {
IMPLEMENTS_MRPT_OBJECT(CStoppingDistanceLimiter, risknav::common::CSpeedLimiter,
                       risknav::sim)

void CStoppingDistanceLimiter::TOptions::declare(Visitor& v) {
    v.flag(enabled, "enabled", "the safety stop acts");
    v.number(margin, "margin", TRange::closed(0, 10, "m"), "beta, added to d_stop");
    v.number(lateral_margin, "lateral_margin", TRange::closed(0, 2, "m"),
             "swept corridor half-width = radius + this");
    v.choice(corridor, "corridor", {"straight", "path", "both"},
             "the swept corridor along the heading, the controller's path, or the "
             "nearer of the two");
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

double CStoppingDistanceLimiter::freeDistance(
    const std::vector<mrpt::math::TPoint2D>& pts, const TRobotOptions& robot) const {
    const double halfW = robot.radius + options.lateral_margin;
    double d = std::numeric_limits<double>::infinity();
    for (const auto& p : pts)
        if (p.x > 0 && std::abs(p.y) <= halfW)
            d = std::min(d, p.x - robot.radius - options.margin);
    return d;
}

double CStoppingDistanceLimiter::freeDistanceAlong(
    const std::vector<mrpt::math::TPoint2D>& pts,
    const std::vector<mrpt::math::TPose2D>& path, const std::vector<double>& dist,
    const TRobotOptions& robot) const {
    // The first path pose whose disc (radius + lateral_margin) holds a
    // sensed point that the robot's disc now does not (a point already
    // beside the robot does not stop it from moving away).
    const double halfW = robot.radius + options.lateral_margin;
    const double h2 = halfW * halfW;
    for (size_t i = 1; i < path.size() && i < dist.size(); i++)
        for (const auto& p : pts) {
            const double dx = p.x - path[i].x, dy = p.y - path[i].y;
            if (dx * dx + dy * dy <= h2 && p.x * p.x + p.y * p.y > h2)
                return std::max(0.0, dist[i] - options.margin);
        }
    return std::numeric_limits<double>::infinity();
}

TSpeedLimit CStoppingDistanceLimiter::impl_limit(const TSpeedLimitInput& in) const {
    if (!options.enabled || in.desiredSpeed <= 0)
        return {in.desiredSpeed, ""};
    // The nearest sensed point in the swept corridor ahead: the highest speed
    // that still stops before it (eqs. 1-4 solved for v). A robot slower
    // than that is not limited, exactly when blocked() is false.
    double d = std::numeric_limits<double>::infinity();
    std::vector<mrpt::math::TPoint2D> pts;
    if (in.scan)
        pts = mapping::scanToRobotFrame(*in.scan);
    if (in.obstacles) {
        const auto& xs = in.obstacles->getPointsBufferRef_x();
        const auto& ys = in.obstacles->getPointsBufferRef_y();
        for (size_t i = 0; i < xs.size(); i++)
            pts.push_back({double(xs[i]), double(ys[i])});
    }
    const bool havePath = in.path.size() >= 2;
    if (!havePath || options.corridor != "path")
        d = freeDistance(pts, *in.robot);
    if (havePath && options.corridor != "straight")
        d = std::min(d, freeDistanceAlong(pts, in.path, in.pathDistance, *in.robot));
    if (!(stoppingDistance(in.desiredSpeed, in.robot->t_delay, in.robot->decel) > d))
        return {in.desiredSpeed, ""};
    const double v = std::min(in.desiredSpeed,
                              maxStoppableSpeed(d, in.robot->t_delay, in.robot->decel));
    char why[96];
    std::snprintf(why, sizeof(why), "obstacle within the stopping distance (%.2f m free)",
                  std::max(0.0, d));
    return {v, why};
}

void registerAllClasses_sim() {
    common::registerAllClasses_common();
    mrpt::rtti::registerClass(CLASS_ID(CStoppingDistanceLimiter));
}

}  // namespace risknav::sim
