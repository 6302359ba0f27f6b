#pragma once
#include <mrpt/math/TPoint2D.h>

#include <optional>
#include <vector>

namespace risknav::nav {
/** Beyond MRPT: a heading to turn to, in place, that leads away from obstacle
 * points inside (or at the edge of) the robot's shape.
 *
 * With points inside its shape, MRPT 2.5.8's engine (COLL_BEH_BACK_AWAY)
 * takes only paths whose first step leaves every such point; a robot facing
 * a door post it stopped beside has none among its forward-only PTGs, so
 * MRPT reports an apparent collision every cycle and never moves. Turned to
 * a heading that points more than 90 deg + `extra` away from the bearing of
 * each point, the forward paths leave them.
 *
 * `near`: the points (robot frame, [m]); `preferred`: the heading wanted
 * (robot frame, [rad], e.g. toward the target); `maxOff`: the farthest from
 * `preferred` the result may be ([rad], <= pi). Returns the admissible
 * heading (robot frame, in (-pi, pi]) nearest `preferred`, or nullopt when
 * `near` is empty or none is admissible within `maxOff` (boxed in).
 * Pure; exact: every candidate is checked against every point. */
std::optional<double> escapeHeading(const std::vector<mrpt::math::TPoint2D>& near,
                                    double preferred, double extra, double maxOff);
}  // namespace risknav::nav
