#include <risknav/common/config_read.h>
#include <risknav/sim/CRouteFollower.h>

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

using namespace risknav::common;
using mrpt::math::TPoint2D;

namespace risknav::sim {
void CRouteFollower::TOptions::declare(Visitor& v) {
    v.numbers(waypoints, "waypoints", TRange::closed(-1e6, 1e6, "m"),
              "x0 y0 x1 y1 ... of one pass", TCount{4, 2, 0, true});
    v.number(speed, "speed", {0, 5, true, false, "m/s"},
             "commanded speed on every segment");
    v.numbers(speeds, "speeds", {0, 5, true, false, "m/s"},
              "optional: one speed per segment (mode loop: one more)");
    v.integer(laps, "laps", TRange::closed(1, 10000),
              "passes over the route (1 for mode once)");
    v.choice(mode, "mode", {"once", "loop", "back_and_forth"}, "how the route repeats");
    v.number(goal_tolerance, "goal_tolerance", TRange::closed(0.01, 2, "m"),
             "a waypoint counts as reached within this distance");
    v.number(heading_gain, "heading_gain", TRange::closed(0.1, 20, "1/s"),
             "omega = gain x heading error");
    v.number(turn_in_place_deg, "turn_in_place_deg", TRange::closed(5, 180, "deg"),
             "heading errors above this: turn in place");
    v.optionalNumber(start_heading_deg, "start_heading_deg",
                     TRange::closed(-180, 180, "deg"),
                     "optional; default: towards the second waypoint");
}

void CRouteFollower::TOptions::validateRules() const {
    const size_t nSeg = waypoints.size() / 2 - (mode == "loop" ? 0 : 1);
    std::string list;
    for (double x : speeds)
        list += (list.empty() ? "" : " ") + numberText(x);
    checkRule(speeds.empty() || speeds.size() == nSeg, section, "speeds", list,
              "needs one speed per segment (" + std::to_string(nSeg) + ")");
    checkRule(mode != "once" || laps == 1, section, "laps", std::to_string(laps),
              "must be 1 when mode = once");
}

std::vector<TPoint2D> CRouteFollower::waypoints() const {
    std::vector<TPoint2D> w;
    for (size_t i = 0; i + 1 < options.waypoints.size(); i += 2)
        w.emplace_back(options.waypoints[i], options.waypoints[i + 1]);
    return w;
}

void CRouteFollower::reset() {
    const auto w = waypoints();
    const size_t n = w.size();
    auto segSpeed = [&](size_t seg) {
        return options.speeds.empty() ? options.speed : options.speeds[seg];
    };
    m_points = {w.front()};
    m_legSpeed = {0.0};
    auto add = [&](const TPoint2D& p, double v) {
        m_points.push_back(p);
        m_legSpeed.push_back(v);
    };
    for (int lap = 0; lap < options.laps; lap++) {
        for (size_t i = 1; i < n; i++)
            add(w[i], segSpeed(i - 1));
        if (options.mode == "loop")
            add(w[0], segSpeed(n - 1));
        else if (options.mode == "back_and_forth")
            for (size_t i = n - 1; i-- > 0;)
                add(w[i], segSpeed(i));
    }
    m_idx = 1;
}

mrpt::math::TPose2D CRouteFollower::startPose() const {
    const auto w = waypoints();
    const double h = options.start_heading_deg
                         ? *options.start_heading_deg * M_PI / 180.0
                         : std::atan2(w[1].y - w[0].y, w[1].x - w[0].x);
    return {w[0].x, w[0].y, h};
}

double CRouteFollower::length() const {
    double L = 0;
    for (size_t i = 1; i < m_points.size(); i++)
        L += std::hypot(m_points[i].x - m_points[i - 1].x,
                        m_points[i].y - m_points[i - 1].y);
    return L;
}

void CRouteFollower::compute(const mrpt::math::TPose2D& pose, double maxW, double decel,
                             double& v, double& w) {
    v = w = 0;
    while (!finished() && std::hypot(m_points[m_idx].x - pose.x,
                                     m_points[m_idx].y - pose.y) < options.goal_tolerance)
        m_idx++;
    if (finished())
        return;
    const TPoint2D& tgt = m_points[m_idx];
    const double dist = std::hypot(tgt.x - pose.x, tgt.y - pose.y);
    const double err =
        mrpt::math::wrapToPi(std::atan2(tgt.y - pose.y, tgt.x - pose.x) - pose.phi);
    const double turnLim = options.turn_in_place_deg * M_PI / 180.0;
    w = std::clamp(options.heading_gain * err, -maxW, maxW);
    if (std::abs(err) > turnLim)
        return;  // turn in place
    v = m_legSpeed[m_idx] * std::cos(err);
    // Corner ahead (or the end): arrive slowly enough to turn in place / stop.
    bool sharp = m_idx + 1 >= m_points.size();
    if (!sharp) {
        const TPoint2D& nxt = m_points[m_idx + 1];
        const double a1 =
            std::atan2(tgt.y - m_points[m_idx - 1].y, tgt.x - m_points[m_idx - 1].x);
        const double a2 = std::atan2(nxt.y - tgt.y, nxt.x - tgt.x);
        sharp = std::abs(mrpt::math::wrapToPi(a2 - a1)) > turnLim;
    }
    if (sharp)
        v = std::min(
            v, std::max(0.03,
                        std::sqrt(2.0 * decel *
                                  std::max(0.0, dist - 0.5 * options.goal_tolerance))));
}

}  // namespace risknav::sim
