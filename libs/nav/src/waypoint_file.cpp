#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/config_read.h>
#include <risknav/nav/waypoint_file.h>

#include <algorithm>
#include <cstdio>
#include <memory>

using namespace risknav::common;

namespace risknav::nav {
void readWaypointFile(const std::string& path, double tol,
                      mrpt::nav::TWaypointSequence& seq,
                      std::map<size_t, TWaypointTag>& tags) {
    seq = {};
    tags.clear();
    std::unique_ptr<CIniConfig> f;
    try {
        f = std::make_unique<CIniConfig>(path);
    } catch (const CBadInputError& e) {
        throw CBadInputError(std::string("[Navigate] route_file: ") + e.what());
    }
    if (!f->sectionExists("Waypoints"))
        throw CBadInputError(path +
                             ": no [Waypoints] section (MRPT's TWaypointSequence)");
    const int n =
        readInt(*f, "Waypoints", "waypoint_count", -1, TRange::closed(1, 10000));
    if (n < 1)
        throw CBadInputError(path +
                             ": [Waypoints] waypoint_count: required key is missing");
    // MRPT's TWaypointSequence keys (TWaypointSequence::save / load), read
    // strictly: a missing or malformed number is an error, not a 0.
    const std::string W = "Waypoints";
    for (int i = 0; i < n; i++) {
        char pre[16];
        std::snprintf(pre, sizeof(pre), "wp%03d_", i);
        const std::string k(pre);
        if (!f->hasKey(W, k + "target_x") || !f->hasKey(W, k + "target_y"))
            throw CBadInputError(path + ": [Waypoints] " + k + "target_x / " + k +
                                 "target_y: required key is missing (" +
                                 std::to_string(n) + " waypoints)");
        const double x =
            readDouble(*f, W, k + "target_x", 0, TRange::closed(-1e5, 1e5, "m"));
        const double y =
            readDouble(*f, W, k + "target_y", 0, TRange::closed(-1e5, 1e5, "m"));
        // MRPT's reactive engine does not stop within a few cm: at least
        // goal_tolerance.
        const double d = std::max(tol, readDouble(*f, W, k + "allowed_distance", tol,
                                                  TRange::closed(0.001, 100, "m")));
        const bool skip = readBool(*f, W, k + "allow_skip", true);
        // MRPT's speed at the approach (TargetInfo::targetDesiredRelSpeed):
        // MRPT 2.5.8 slows to it only within its holonomic method's
        // TARGET_SLOW_APPROACHING_DISTANCE (0.1 m in MRPT's shipped file) of
        // the waypoint, inside the allowed distance where the waypoint is
        // already reached. It changed nothing (the office route's cycles.csv
        // was the same with 0.05 and 1), so only MRPT's default 1 is taken.
        const double ratio =
            readDouble(*f, W, k + "speed_ratio", 1, TRange{0, 1, true, false, ""});
        if (ratio != 1)
            throwBadKey(
                *f, W, k + "speed_ratio", readString(*f, W, k + "speed_ratio", ""),
                "only 1: MRPT 2.5.8 slows to it only within 0.1 m of the "
                "waypoint (TARGET_SLOW_APPROACHING_DISTANCE), where it is already "
                "reached (allowed distance >= goal_tolerance), so it has no effect; "
                "remove the key");
        // the robot's pose is in "map" (CSimRobotInterface): a waypoint in
        // another frame would need a transform MRPT's navigator cannot get here
        const std::string frame = readString(*f, W, k + "target_frame_id", "map");
        if (frame != "map")
            throw CBadInputError(path + ": [Waypoints] " + k + "target_frame_id = '" +
                                 frame +
                                 "': only 'map' (the frame the robot's pose is in)");
        // MRPT aligns to a waypoint's heading with its robot interface's
        // getAlignCmd(), which for MRPT's simulated diff-drive robot is a
        // holonomic command the robot refuses: MRPT would wait for ever
        if (f->hasKey(W, k + "target_heading"))
            throw CBadInputError(path + ": [Waypoints] " + k +
                                 "target_heading: not supported (MRPT's in-place "
                                 "alignment needs a holonomic robot); remove the key");
        seq.waypoints.emplace_back(x, y, d, skip, std::nullopt, ratio);
        const std::string vk = "waypoint_" + std::to_string(i);
        if (f->sectionExists("Viewpoints") && f->hasKey("Viewpoints", vk))
            tags[size_t(i)] = {"viewpoint", readString(*f, "Viewpoints", vk, "")};
    }
    f->throwOnUnreadKeys({"Waypoints", "Viewpoints"});
}

}  // namespace risknav::nav
