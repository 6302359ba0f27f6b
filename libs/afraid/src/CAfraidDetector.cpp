#include <risknav/afraid/CAfraidDetector.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>

#include <mrpt/poses/CPose2D.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::afraid {
void CAfraidDetector::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                                   const std::string& s) {
    t_delay = readDouble(c, s, "t_delay", t_delay, TRange::closed(0, 10, "s"));
    decel = readDouble(c, s, "decel", decel, {0, 20, true, false, "m/s^2"});
    beta = readDouble(c, s, "beta", beta, TRange::closed(0, 10, "m"));
    half_width = readDouble(c, s, "half_width", half_width, TRange::closed(0.01, 5, "m"));
    foot_step = readInt(c, s, "foot_step", foot_step, TRange::closed(1, 1000));
    diff_threshold =
        readDouble(c, s, "diff_threshold", diff_threshold, TRange::nonNegative("m"));
    directions = readInt(c, s, "directions", directions, TRange::closed(3, 3601));
    unexpected_margin = readDouble(c, s, "unexpected_margin", unexpected_margin,
                                   TRange::closed(0, 5, "m"));
}

std::vector<TPoint> CAfraidDetector::robotFramePoints(
    const mrpt::obs::CObservation2DRangeScan& scan) {
    std::vector<TPoint> pts;
    const size_t n = scan.getScanSize();
    const double a0 = -0.5 * scan.aperture, da = n > 1 ? scan.aperture / (n - 1) : 0.0;
    const double sx = scan.sensorPose.x(), sy = scan.sensorPose.y(),
                 syaw = scan.sensorPose.yaw();
    const double dir = scan.rightToLeft ? 1.0 : -1.0;
    for (size_t i = 0; i < n; i++) {
        if (!scan.getScanRangeValidity(i))
            continue;
        const double r = scan.getScanRange(i), a = syaw + dir * (a0 + da * i);
        pts.push_back({sx + r * std::cos(a), sy + r * std::sin(a)});
    }
    return pts;
}

TAfraidStep CAfraidDetector::step(const mrpt::obs::CObservation2DRangeScan& scan,
                                  const mrpt::math::TPose2D& pose, double speed,
                                  const mrpt::maps::COccupancyGridMap2D& map) {
    const auto& o = options;
    TAfraidStep s;
    s.speed = std::max(0.0, speed);
    s.dStop = stoppingDistance(s.speed, o.t_delay, o.decel);

    // The scan the map predicts at the localized pose (same geometry).
    mrpt::obs::CObservation2DRangeScan expected = scan;
    map.laserScanSimulator(expected, mrpt::poses::CPose2D(pose), 0.5f, scan.getScanSize(),
                           0.0f);
    const auto actual = robotFramePoints(scan);
    const auto predicted = robotFramePoints(expected);

    s.obsCur = obsCur(actual, s.dStop, o.beta, o.half_width);
    s.obsPredict = obsPredict(m_history, size_t(o.foot_step));
    s.actualArea = nonBlockedArea(actual, s.dStop, o.beta, o.half_width, o.directions);
    s.expectedArea =
        nonBlockedArea(predicted, s.dStop, o.beta, o.half_width, o.directions);
    s.diff = std::abs(s.expectedArea - s.actualArea);  // eq. (10)
    s.afraid = afraidFlag(s.obsCur, s.obsPredict, s.diff, o.diff_threshold);

    // Where the unexpected obstacle is: the nearest ray in the collision area
    // that is shorter than the map says (an obstacle the map does not have).
    double best = 1e9;
    const size_t n = scan.getScanSize();
    const double a0 = -0.5 * scan.aperture, da = n > 1 ? scan.aperture / (n - 1) : 0.0;
    const double dir = scan.rightToLeft ? 1.0 : -1.0;
    const mrpt::poses::CPose2D robot(pose);
    for (size_t i = 0; i < n; i++) {
        if (!scan.getScanRangeValidity(i))
            continue;
        const double r = scan.getScanRange(i);
        const double re =
            expected.getScanRangeValidity(i) ? expected.getScanRange(i) : scan.maxRange;
        if (r > re - o.unexpected_margin)
            continue;
        const double a = scan.sensorPose.yaw() + dir * (a0 + da * i);
        const double px = scan.sensorPose.x() + r * std::cos(a),
                     py = scan.sensorPose.y() + r * std::sin(a);
        if (px <= 0 || std::abs(py) > o.half_width ||
            px >= s.dStop + o.beta + o.half_width)
            continue;
        if (px < best) {
            best = px;
            const auto w = robot + mrpt::poses::CPose2D(px, py, 0);
            s.obstacleX = w.x();
            s.obstacleY = w.y();
            s.obstacleFound = true;
        }
    }
    m_history.push_back(s.obsCur);
    while (m_history.size() > size_t(o.foot_step))
        m_history.pop_front();
    return s;
}

}  // namespace risknav::afraid
