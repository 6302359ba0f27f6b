#include <risknav/common/config_read.h>
#include <risknav/speed/TExploreOptions.h>

using namespace risknav::common;

namespace risknav::speed {
void TExploreOptions::declare(Visitor& v) {
    const TRange coordinate = TRange::closed(-1e6, 1e6);
    v.numbers(start, "start", coordinate, "x [m] y [m] heading [deg] (world frame)");
    v.numbers(destinations, "destinations", coordinate,
              "x y pairs [m] visited in order (world frame), 1 to 100");
    v.words(modes, "modes", {"adaptive", "fixed"},
            "adaptive and / or fixed (one run per candidate speed)");
    v.choice(ego_motion, "ego_motion", {"scan_matching", "odometry", "ground_truth"},
             "how the robot knows its motion");
    v.number(local_map_size, "local_map_size", TRange::closed(2, 100, "m"),
             "side of the robot-centred grids");
    v.number(local_map_resolution, "local_map_resolution", TRange::closed(0.01, 0.5, "m"),
             "their cell");
    v.number(memory_size, "memory_size", TRange::closed(0, 1000, "m"),
             "side of the coarse free-space memory at least (0 = none)");
    v.number(memory_resolution, "memory_resolution", TRange::closed(0.05, 5, "m"),
             "its cell");
    v.number(sim_dt, "sim_dt", TRange{0, 1, true, false, "s"},
             "physics step inside a cycle");
    v.number(duration_max, "duration_max", TRange{0, 36000, true, false, "s"},
             "simulated, per mode");
    v.number(goal_tolerance, "goal_tolerance", TRange{0, 10, true, false, "m"},
             "a destination is reached when the TRUE pose is within this where the robot "
             "believed it had arrived");
    v.number(arrival_radius, "arrival_radius", TRange{0, 10, true, false, "m"},
             "the robot believes it has arrived within this (at most goal_tolerance)");
    v.number(
        unreachable_after, "unreachable_after", TRange::closed(0, 3600, "s"),
        "of \"unreachable\" (no path, no frontier) before a destination is given up");
    v.number(
        not_approaching_timeout, "not_approaching_timeout", TRange::closed(0, 36000, "s"),
        "a destination not come 0.5 m nearer to for this long is given up (0 = never)");
    v.flag(look_around, "look_around", "turn once on the spot before setting off");
    v.integer(max_snapshots, "max_snapshots", TRange::closed(0, 1000),
              "snapshots/ of the adaptive mode (0 = none)");
    v.seed(seed, "seed", "the run's random seed (--seed overrides)");
}

void checkLocalMapSizes(const std::string& s, double localMapSize,
                        double localMapResolution, double memorySize,
                        double memoryResolution) {
    checkRule(localMapSize / localMapResolution <= 2000, s, "local_map_size",
              numberText(localMapSize), "at most 2000 cells a side");
    checkRule(memorySize / memoryResolution <= 4096, s, "memory_size",
              numberText(memorySize),
              "more than 4096 memory cells a side (raise memory_resolution)");
    // a memory smaller than the local map, or of a few cells, remembers nothing
    checkRule(
        memorySize == 0 || memorySize >= localMapSize, s, "memory_size",
        numberText(memorySize),
        "must be 0 (none) or at least local_map_size = " + numberText(localMapSize));
    checkRule(memoryResolution <= localMapSize / 4, s, "memory_resolution",
              numberText(memoryResolution),
              "must be at most local_map_size / 4 = " + numberText(localMapSize / 4));
}

void TExploreOptions::validateRules() const {
    checkRule(start.size() == 3, section, "start",
              std::to_string(start.size()) + " values", "needs x y heading_deg");
    checkRule(!destinations.empty() && destinations.size() % 2 == 0 &&
                  destinations.size() <= 200,
              section, "destinations", std::to_string(destinations.size()) + " values",
              "needs 1 to 100 x y pairs");
    checkLocalMapSizes(section, local_map_size, local_map_resolution, memory_size,
                       memory_resolution);
    checkRule(arrival_radius <= goal_tolerance, section, "arrival_radius",
              numberText(arrival_radius),
              "must be at most goal_tolerance = " + numberText(goal_tolerance));
}
}  // namespace risknav::speed
