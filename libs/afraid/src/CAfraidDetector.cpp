#include <risknav/afraid/CAfraidDetector.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/scan_points.h>

#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <cmath>

using namespace risknav::common;

namespace risknav::afraid {
namespace {
// Headings within this of the current one count as "the same way" [rad].
constexpr double kSameHeading = 15 * M_PI / 180;
}  // namespace

void CAfraidDetector::TOptions::declare(Visitor& v) {
    v.number(beta, "beta", TRange::closed(0, 10, "m"), "marginal distance of eq. (5)");
    v.number(lateral_margin, "lateral_margin", TRange::closed(0, 5, "m"),
             "the area's half-width = [Robot] radius + this");
    v.integer(foot_step, "foot_step", TRange::closed(1, 1000),
              "cycles of eq. (6): an unexpected obstacle seen this recently is tracked");
    v.number(diff_threshold, "diff_threshold",
             TRange::closed(0, 1, "(a fraction of the collision-possible area)"),
             "eq. (11): |E_area - A_area| as a fraction of the whole area");
    v.integer(directions, "directions", TRange::closed(3, 3601),
              "directions over the forward half-plane in eq. (9)");
    v.number(unexpected_margin, "unexpected_margin", TRange::closed(0, 5, "m"),
             "a scan point this close to a map obstacle is the map's, even from a "
             "perfect pose");
    v.number(explain_sigmas, "explain_sigmas", TRange::closed(0, 10),
             "pose standard deviations that still explain a point's offset");
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
                                  const mrpt::math::TPose2D& pose,
                                  const mrpt::math::CMatrixDouble33& cov, double speed,
                                  const mrpt::maps::COccupancyGridMap2D& map,
                                  const mapping::CDistanceField& field) {
    const auto& o = options;
    TAfraidStep s;
    // d_stop from the highest recent speed (eqs. 1-3): braking for an obstacle
    // must not shrink the area the obstacle is looked for in.
    // Only the speeds with which the robot was heading the same way count: a
    // robot that stops and turns in place sweeps its area over things it was
    // not driving towards.
    m_speeds.emplace_back(std::max(0.0, speed), pose.phi);
    while (m_speeds.size() > size_t(o.foot_step) + 1)
        m_speeds.pop_front();
    s.speed = 0;
    for (const auto& [v, phi] : m_speeds)
        if (std::abs(mrpt::math::wrapToPi(phi - pose.phi)) <= kSameHeading)
            s.speed = std::max(s.speed, v);
    s.dStop = stoppingDistance(s.speed, robot.t_delay, robot.decel);
    s.area = {robot.radius + s.dStop + o.beta, halfWidth()};

    // The scan the map predicts at the localized pose (same geometry).
    mrpt::obs::CObservation2DRangeScan expected = scan;
    map.laserScanSimulator(expected, mrpt::poses::CPose2D(pose), 0.5f, scan.getScanSize(),
                           0.0f);
    const auto predicted = mapping::scanToRobotFrame(expected);

    // The actual scan, with the rays the map explains within the pose
    // uncertainty replaced by the map's prediction.
    const double sigmaXY = std::sqrt(std::max(0.0, std::max(cov(0, 0), cov(1, 1))));
    const double sigmaPhi = std::sqrt(std::max(0.0, cov(2, 2)));
    const mrpt::poses::CPose2D robotPose(pose);
    std::vector<mrpt::math::TPoint2D> actual;
    actual.reserve(scan.getScanSize());
    double nearest = 1e9;
    for (size_t i = 0; i < scan.getScanSize(); i++) {
        if (!scan.getScanRangeValidity(i))
            continue;
        const double range = scan.getScanRange(i), a = mapping::scanRayAngle(scan, i);
        const mrpt::math::TPoint2D p(scan.sensorPose.x() + range * std::cos(a),
                                     scan.sensorPose.y() + range * std::sin(a));
        const auto w = robotPose + mrpt::poses::CPose2D(p.x, p.y, 0);
        const double tol =
            o.unexpected_margin + o.explain_sigmas * (sigmaXY + range * sigmaPhi);
        // On the surface of a map obstacle within the tolerance: in front of it
        // (clearance) or inside it (depth; the pose is too far ahead).
        const bool explained =
            field.clearanceAt(w.x(), w.y()) <= tol && field.depthAt(w.x(), w.y()) <= tol;
        if (explained && expected.getScanRangeValidity(i)) {
            const double re = expected.getScanRange(i);
            actual.emplace_back(scan.sensorPose.x() + re * std::cos(a),
                                scan.sensorPose.y() + re * std::sin(a));
            s.explained++;
            continue;
        }
        actual.push_back(p);
        if (explained || !s.area.contains(p))
            continue;
        // An obstacle the map does not have, inside the collision area: the
        // nearest one is where the event happens.
        s.unexpected++;
        if (p.x < nearest) {
            nearest = p.x;
            s.obstacleAlong = p.x;
            s.obstacleX = w.x();
            s.obstacleY = w.y();
            s.obstacleFound = true;
        }
    }

    // Eq. (5) on what the robot really senses; eqs. (8)-(10) on the areas.
    std::vector<mrpt::math::TPoint2D> raw = mapping::scanToRobotFrame(scan);
    s.obsCur = obsCur(raw, s.area);
    s.obsPredict = obsPredict(m_history, size_t(o.foot_step));
    s.actualArea = nonBlockedArea(actual, s.area, o.directions);
    s.expectedArea = nonBlockedArea(predicted, s.area, o.directions);
    s.diff = areaDifference(s.expectedArea, s.actualArea, s.area, o.directions);
    s.afraid = afraidFlag(s.obsCur, s.obsPredict, s.diff, o.diff_threshold);

    // Eq. (6)'s history tracks the UNEXPECTED obstacles (obs_cur = 0 and the
    // map does not explain the area: diff > threshold), not every obstacle:
    // a mapped wall that enters the collision area (a dead end, a corner) must
    // not hide a person who steps out next to it, and a person who enters
    // from the side is an event in the first frame in which it blocks enough
    // of the area, not lost because it touched the area's edge a frame before.
    m_history.push_back(s.obsCur == 0 && s.diff > o.diff_threshold ? 0 : 1);
    while (m_history.size() > size_t(o.foot_step))
        m_history.pop_front();
    return s;
}

}  // namespace risknav::afraid
