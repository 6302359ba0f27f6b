#pragma once
#include <mrpt/nav/reactive/TWaypoint.h>

#include <cstddef>
#include <map>
#include <string>

namespace risknav::nav {
/** A waypoint the route tags: a viewpoint (M4) or a sensing point (M2). */
struct TWaypointTag {
    std::string kind;    ///< viewpoint | sensing
    std::string detail;  ///< strategy and landmarks, or the sensing point's name
    double sigmaX = 0, sigmaY = 0, sigmaPhi = 0;  ///< sensing: the pose fix's sigmas
};

/** Reads an MRPT TWaypointSequence file (section [Waypoints]:
 * waypoint_count, wpNNN_target_x / _target_y / _allowed_distance /
 * _allow_skip / _speed_ratio / _target_frame_id, the keys of MRPT's
 * TWaypointSequence::save / load) strictly: a missing or malformed number,
 * a speed_ratio other than 1 (MRPT 2.5.8 applies its approach speed only
 * within 0.1 m of a waypoint, where it is already reached), a frame other
 * than "map", a target_heading (MRPT's diff-drive simulator cannot align),
 * a count beyond 10000 or an unknown key is a CBadInputError naming the file
 * (MRPT's own load() would read "5abc" as 5). Each waypoint's allowed
 * distance is at least `minTolerance` [m] (MRPT's reactive engine does not
 * stop within a few cm). [Viewpoints] waypoint_N = "strategy landmarks pans"
 * (risknav-viewpoint-plan) tags viewpoint N. */
void readWaypointFile(const std::string& path, double minTolerance,
                      mrpt::nav::TWaypointSequence& seq,
                      std::map<size_t, TWaypointTag>& tags);

}  // namespace risknav::nav
