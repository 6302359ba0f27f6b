#include <risknav/common/config_read.h>
#include <risknav/nav/CTurnSupervisor.h>
#include <risknav/nav/escape_heading.h>

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>

namespace risknav::nav {
using common::numberText;

std::vector<mrpt::math::TPoint2D> CTurnSupervisor::pointsNearShape(
    const mrpt::maps::CSimplePointsMap& obstacles, double shapeRadius) {
    const double reach = shapeRadius + kShapeEdge;
    std::vector<mrpt::math::TPoint2D> near;
    const auto& xs = obstacles.getPointsBufferRef_x();
    const auto& ys = obstacles.getPointsBufferRef_y();
    for (size_t k = 0; k < xs.size(); k++)
        if (std::hypot(xs[k], ys[k]) <= reach)
            near.emplace_back(xs[k], ys[k]);
    return near;
}

void CTurnSupervisor::endTurn() {
    m_turning = m_unsticking = m_startTurning = false;
    m_escapeHeading.reset();
}

std::optional<CTurnSupervisor::TTurn> CTurnSupervisor::step(const TInput& in) {
    const auto& pose = in.pose;
    const auto& target = in.target;
    const double now = in.now;
    auto guide = [&]() -> std::optional<mrpt::math::TPoint2D> {
        return in.guidePoint ? in.guidePoint() : std::nullopt;
    };
    // stuck: neither 5 cm nor 5 deg of motion for unstick_time (a robot MRPT
    // dithers by +-5 deg is not caught: turned to a target behind a corner,
    // MRPT's way round it was lost); a clock gone back, or a new run, starts
    // the watch again
    if (m_stillPose && now < m_stillSince)
        m_unstuck.reset(), m_guidePausedAt.reset();
    if (!m_stillPose || now < m_stillSince ||
        std::hypot(pose.x - m_stillPose->x, pose.y - m_stillPose->y) > 0.05 ||
        std::abs(mrpt::math::wrapToPi(pose.phi - m_stillPose->phi)) > 5 * M_PI / 180) {
        m_stillPose = pose;
        m_stillSince = now;
    }
    const double stillFor = now - m_stillSince;
    const bool stuck = options.unstick_time > 0 && stillFor >= options.unstick_time;
    // A robot stuck while MRPT is aimed at a guide point (e.g. frozen at a
    // slant in the entrance of a passage the way hugs) is aimed straight at
    // the waypoint again until it has moved 0.5 m or has a new target
    // (office seed 8: 45 s frozen between the desks).
    if (m_guidePausedAt && (std::hypot(pose.x - m_guidePausedAt->first.x,
                                       pose.y - m_guidePausedAt->first.y) > 0.5 ||
                            std::hypot(m_guidePausedAt->second.x - target.x,
                                       m_guidePausedAt->second.y - target.y) > 1e-6))
        m_guidePausedAt.reset();
    if (stuck && !m_guidePausedAt && guide())
        m_guidePausedAt = {mrpt::math::TPoint2D(pose.x, pose.y), target};
    // turned to where MRPT is aimed: the guide point when there is one,
    // else the target
    const mrpt::math::TPoint2D aim = guide().value_or(target);
    double bearing =
        mrpt::math::wrapToPi(std::atan2(aim.y - pose.y, aim.x - pose.x) - pose.phi);
    const double aimBearing = bearing;
    // an escape turn (below) turns to its own heading
    if (m_escapeHeading)
        bearing = mrpt::math::wrapToPi(*m_escapeHeading - pose.phi);
    const double deg = std::abs(bearing) * 180 / M_PI;
    // At most kMaxUnstickTurns per target, counted again once the robot got
    // 0.5 m nearer to it than at the nearest turn: at a target behind a
    // wall, turning to it for ever would hide MRPT's own verdict (its
    // timeout approaching the target, way_seems_blocked) and run to the end;
    // one turn only left U-corridor robots creeping for 100 s at a bend that
    // a second turn gets them out of.
    const double dist = std::hypot(target.x - pose.x, target.y - pose.y);
    const bool sameTarget =
        m_unstuck &&
        std::hypot(m_unstuck->target.x - target.x, m_unstuck->target.y - target.y) < 1e-6;
    if (!sameTarget)
        m_unstuck.reset();  // a new target (or the same one again later)
    const bool nearer = sameTarget && dist < m_unstuck->distance - 0.5;
    const bool mayUnstick = !sameTarget || nearer || m_unstuck->turns < kMaxUnstickTurns;
    const double limitDeg = options.turn_in_place_deg;
    const double unstickDeg = options.unstick_heading_deg;
    const double startDeg = options.start_turn_deg;
    // the reference is the nearest the robot was at a turn: pushed back and
    // returning does not count as getting nearer
    auto countTurn = [&] {
        m_unstuck = sameTarget && !nearer
                        ? TUnstick{target, std::min(dist, m_unstuck->distance),
                                   m_unstuck->turns + 1}
                        : TUnstick{target, dist, 1};
    };
    const bool standing = in.speed < 0.05;
    if (m_turning) {
        m_turning = deg > (m_unsticking     ? unstickDeg
                           : m_startTurning ? startDeg
                                            : limitDeg) /
                              3;
        if (!m_turning)
            m_escapeHeading.reset();
    } else if (limitDeg > 0 && deg > limitDeg) {
        m_turning = true, m_unsticking = false, m_startTurning = false;
    } else if (startDeg > 0 && deg > startDeg && standing && !m_escapeHeading) {
        m_turning = true, m_unsticking = false, m_startTurning = true;
    } else if (stuck && deg > unstickDeg && mayUnstick) {
        m_turning = true, m_unsticking = true;
        countTurn();
        m_unstickReason = "target " + numberText(std::round(deg)) + " deg off after " +
                          numberText(std::round(stillFor)) + " s without motion";
    } else if (stuck && mayUnstick) {
        // Facing its target, yet still: obstacle points at (or in) MRPT's
        // robot shape that every forward path nears (rooms M1 seed 8:
        // standing in a doorway 0.33 m from a post, MRPT's "apparent
        // collision" for 45 s, then its timeout). Turned until its heading
        // leads away from each of them (the first step of every forward path
        // leaves them), as near the target as that allows and within
        // turn_in_place_deg of it (MRPT's forward-only PTGs must still aim
        // at it).
        const double maxOff = limitDeg > 0 ? (limitDeg - unstickDeg) * M_PI / 180 : M_PI;
        const auto near = in.pointsNearShape ? in.pointsNearShape()
                                             : std::vector<mrpt::math::TPoint2D>{};
        if (const auto e = escapeHeading(near, aimBearing, 0.0, maxOff);
            e && std::abs(*e) * 180 / M_PI > unstickDeg / 3) {
            m_turning = true, m_unsticking = true;
            m_escapeHeading = pose.phi + *e;
            bearing = *e;
            countTurn();
            m_unstickReason =
                "obstacle at MRPT's robot shape after " +
                numberText(std::round(stillFor)) +
                " s without motion: turned away from it, " +
                numberText(std::round(std::abs(mrpt::math::wrapToPi(*e - aimBearing)) *
                                      180 / M_PI)) +
                " deg off the target";
        }
    }
    if (!m_turning) {
        endTurn();
        return std::nullopt;
    }
    TTurn t;
    t.angVel = (bearing > 0 ? 1 : -1) * options.turn_rate_deg * M_PI / 180;
    t.unsticking = m_unsticking;
    t.reason = m_unsticking ? m_unstickReason
               : m_startTurning
                   ? "aim " + numberText(std::round(deg)) +
                         " deg off a standing robot, more than start_turn_deg"
                   : "target " + numberText(std::round(deg)) +
                         " deg off, more than turn_in_place_deg";
    return t;
}
}  // namespace risknav::nav
