#pragma once
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <string>
#include <vector>

namespace risknav::nav {
/** What planFollowCommand() asks of the robot. */
struct TFollowCommand {
    double v = 0;          ///< [m/s]
    double w = 0;          ///< [rad/s]
    bool blocked = false;  ///< no safe motion along the plan (v = w = 0)
    std::string what;      ///< "turn" | "drive" | "blocked"
};

/** Beyond the papers and MRPT: one pure-pursuit command along a global plan,
 * for a robot MRPT's engine leaves standing (MRPT 2.5.8 scales its speed to
 * ~1e-4 m/s when every path it may take nears an obstacle within
 * secure_distance_start; in a gap its shape fits by a few cm that is every
 * path, for minutes).
 *
 * `ahead`: the plan from the point nearest the robot on (world, [m]);
 * `obstacles`: sensed points in the robot frame [m]; `clearance`: the least
 * distance [m] from the robot's centre to any of them along the motion (a
 * plan keeps MRPT's shape off the map, so this guards only tracking error
 * and what the map does not hold). The aim is the plan's point `lookahead`
 * [m] ahead (by arc length from the nearest point); more than 30 deg off
 * the heading it is turned to in place at `wMax` (a disc turns without
 * sweeping anything new); else the arc to it at up to `vMax`, slower the
 * more it bends, checked pose by pose (2 cm apart) for `horizon` [s] of
 * motion plus 5 cm against `clearance` (or, for a robot already nearer,
 * against where it stands less 5 mm: it may move on, getting no nearer;
 * never below `floor`, the robot's own body with its sensing error, and a
 * robot already within `floor` against where it stands exactly);
 * halved down to vMax / 8 when not clear; then, more than 3 deg off the
 * aim, turned to it in place (every arc leaves along the heading: one
 * aimed past a door post nears it before it bends), else blocked. The robot
 * is taken as the disc of `clearance`'s radius, which turns in place
 * without nearing anything. Pure. */
TFollowCommand planFollowCommand(const mrpt::math::TPose2D& pose,
                                 const std::vector<mrpt::math::TPoint2D>& ahead,
                                 const std::vector<mrpt::math::TPoint2D>& obstacles,
                                 double clearance, double vMax, double wMax,
                                 double lookahead = 0.5, double horizon = 1.0,
                                 double floor = 0.0);

/** [m] the least distance from the robot's centre to `obstacles` (robot
 * frame at the start) over the unicycle arc of speed v, turn rate w, driven
 * for `distance` [m] (0: the start only), poses 2 cm apart. Pure. */
double arcClearance(const std::vector<mrpt::math::TPoint2D>& obstacles, double v,
                    double w, double distance);
}  // namespace risknav::nav
