#include <risknav/afraid/CAfraidDetector.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/scan_points.h>

#include <mrpt/poses/CPose2D.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::afraid {
void CAfraidDetector::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                                   const std::string& s) {
    beta = readDouble(c, s, "beta", beta);
    lateral_margin = readDouble(c, s, "lateral_margin", lateral_margin);
    foot_step = readInt(c, s, "foot_step", foot_step);
    diff_threshold = readDouble(c, s, "diff_threshold", diff_threshold);
    directions = readInt(c, s, "directions", directions);
    unexpected_margin = readDouble(c, s, "unexpected_margin", unexpected_margin);
}

void CAfraidDetector::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                 const std::string& s) const {
    writeKey(c, s, "beta", beta);
    writeKey(c, s, "lateral_margin", lateral_margin);
    writeKey(c, s, "foot_step", foot_step);
    writeKey(c, s, "diff_threshold", diff_threshold);
    writeKey(c, s, "directions", directions);
    writeKey(c, s, "unexpected_margin", unexpected_margin);
}

void CAfraidDetector::TOptions::validate() const {
    const std::string s = "AfraidDetector";
    checkKey(s, "beta", beta, TRange::closed(0, 10, "m"));
    checkKey(s, "lateral_margin", lateral_margin, TRange::closed(0, 5, "m"));
    checkKey(s, "foot_step", foot_step, TRange::closed(1, 1000));
    checkKey(s, "diff_threshold", diff_threshold, TRange::nonNegative("m"));
    checkKey(s, "directions", directions, TRange::closed(3, 3601));
    checkKey(s, "unexpected_margin", unexpected_margin, TRange::closed(0, 5, "m"));
}

void CAfraidDetector::loadFromConfigFile(const mrpt::config::CConfigFileBase& c) {
    loadOptions(options, c, "AfraidDetector");
    loadOptions(robot, c, "Robot");
}

void CAfraidDetector::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    options.saveToConfigFile(c, "AfraidDetector");
    robot.saveToConfigFile(c, "Robot");
}

void CAfraidDetector::validate() const {
    options.validate();
    robot.validate();
}

TAfraidStep CAfraidDetector::step(const mrpt::obs::CObservation2DRangeScan& scan,
                                  const mrpt::math::TPose2D& pose, double speed,
                                  const mrpt::maps::COccupancyGridMap2D& map) {
    const auto& o = options;
    const double r = halfWidth();
    TAfraidStep s;
    s.speed = std::max(0.0, speed);
    s.dStop = stoppingDistance(s.speed, robot.t_delay, robot.decel);

    // The scan the map predicts at the localized pose (same geometry).
    mrpt::obs::CObservation2DRangeScan expected = scan;
    map.laserScanSimulator(expected, mrpt::poses::CPose2D(pose), 0.5f, scan.getScanSize(),
                           0.0f);
    const auto actual = mapping::scanToRobotFrame(scan);
    const auto predicted = mapping::scanToRobotFrame(expected);

    s.obsCur = obsCur(actual, s.dStop, o.beta, r);
    s.obsPredict = obsPredict(m_history, size_t(o.foot_step));
    s.actualArea = nonBlockedArea(actual, s.dStop, o.beta, r, o.directions);
    s.expectedArea = nonBlockedArea(predicted, s.dStop, o.beta, r, o.directions);
    s.diff = std::abs(s.expectedArea - s.actualArea);  // eq. (10)
    s.afraid = afraidFlag(s.obsCur, s.obsPredict, s.diff, o.diff_threshold);

    // Where the unexpected obstacle is: the nearest ray in the collision area
    // that is shorter than the map says (an obstacle the map does not have).
    double best = 1e9;
    const mrpt::poses::CPose2D robotPose(pose);
    for (size_t i = 0; i < scan.getScanSize(); i++) {
        if (!scan.getScanRangeValidity(i))
            continue;
        const double range = scan.getScanRange(i);
        const double re =
            expected.getScanRangeValidity(i) ? expected.getScanRange(i) : scan.maxRange;
        if (range > re - o.unexpected_margin)
            continue;
        const double a = mapping::scanRayAngle(scan, i);
        const double px = scan.sensorPose.x() + range * std::cos(a),
                     py = scan.sensorPose.y() + range * std::sin(a);
        if (px <= 0 || std::abs(py) > r || px >= s.dStop + o.beta + r)
            continue;
        if (px < best) {
            best = px;
            const auto w = robotPose + mrpt::poses::CPose2D(px, py, 0);
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
