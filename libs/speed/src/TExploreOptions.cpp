#include <risknav/common/config_read.h>
#include <risknav/speed/TExploreOptions.h>

#include <sstream>

using namespace risknav::common;

namespace risknav::speed {
namespace {
std::vector<std::string> words(const std::string& s) {
    std::vector<std::string> w;
    std::istringstream in(s);
    for (std::string x; in >> x;)
        w.push_back(x);
    return w;
}
std::string joined(const std::vector<std::string>& w) {
    std::string s;
    for (const auto& x : w)
        s += (s.empty() ? "" : " ") + x;
    return s;
}
}  // namespace

void TExploreOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                         const std::string& s) {
    section = s;
    start = readNumbers(c, s, "start", start);
    destinations = readNumbers(c, s, "destinations", destinations);
    modes = words(readString(c, s, "modes", joined(modes)));
    ego_motion = readChoice(c, s, "ego_motion", ego_motion,
                            {"scan_matching", "odometry", "ground_truth"});
    local_map_size = readDouble(c, s, "local_map_size", local_map_size);
    local_map_resolution = readDouble(c, s, "local_map_resolution", local_map_resolution);
    memory_size = readDouble(c, s, "memory_size", memory_size);
    memory_resolution = readDouble(c, s, "memory_resolution", memory_resolution);
    sim_dt = readDouble(c, s, "sim_dt", sim_dt);
    duration_max = readDouble(c, s, "duration_max", duration_max);
    goal_tolerance = readDouble(c, s, "goal_tolerance", goal_tolerance);
    arrival_radius = readDouble(c, s, "arrival_radius", arrival_radius);
    unreachable_after = readDouble(c, s, "unreachable_after", unreachable_after);
    not_approaching_timeout =
        readDouble(c, s, "not_approaching_timeout", not_approaching_timeout);
    look_around = readBool(c, s, "look_around", look_around);
    max_snapshots = readInt(c, s, "max_snapshots", max_snapshots);
    seed = uint64_t(readDouble(c, s, "seed", double(seed), TRange::closed(0, kMaxSeed)));
}

void TExploreOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                       const std::string& s) const {
    writeKey(c, s, "start", start);
    writeKey(c, s, "destinations", destinations);
    writeKey(c, s, "modes", joined(modes));
    writeKey(c, s, "ego_motion", ego_motion);
    writeKey(c, s, "local_map_size", local_map_size);
    writeKey(c, s, "memory_size", memory_size);
    writeKey(c, s, "memory_resolution", memory_resolution);
    writeKey(c, s, "local_map_resolution", local_map_resolution);
    writeKey(c, s, "sim_dt", sim_dt);
    writeKey(c, s, "duration_max", duration_max);
    writeKey(c, s, "goal_tolerance", goal_tolerance);
    writeKey(c, s, "arrival_radius", arrival_radius);
    writeKey(c, s, "unreachable_after", unreachable_after);
    writeKey(c, s, "not_approaching_timeout", not_approaching_timeout);
    writeKey(c, s, "look_around", look_around);
    writeKey(c, s, "max_snapshots", max_snapshots);
    writeKey(c, s, "seed", double(seed));
}

void TExploreOptions::validate() const {
    checkRule(start.size() == 3, section, "start",
              std::to_string(start.size()) + " values", "needs x y heading_deg");
    checkKey(section, "start", start, TRange::closed(-1e6, 1e6));
    checkRule(!destinations.empty() && destinations.size() % 2 == 0 &&
                  destinations.size() <= 200,
              section, "destinations", std::to_string(destinations.size()) + " values",
              "needs 1 to 100 x y pairs");
    checkKey(section, "destinations", destinations, TRange::closed(-1e6, 1e6));
    checkRule(!modes.empty(), section, "modes", "", "needs adaptive and / or fixed");
    for (const auto& m : modes)
        checkRule(m == "adaptive" || m == "fixed", section, "modes", m,
                  "each mode is adaptive or fixed");
    checkKey(section, "local_map_size", local_map_size, TRange::closed(2, 100, "m"));
    checkKey(section, "local_map_resolution", local_map_resolution,
             TRange::closed(0.01, 0.5, "m"));
    checkRule(local_map_size / local_map_resolution <= 2000, section, "local_map_size",
              numberText(local_map_size), "at most 2000 cells a side");
    checkKey(section, "memory_size", memory_size, TRange::closed(0, 1000, "m"));
    checkKey(section, "memory_resolution", memory_resolution,
             TRange::closed(0.05, 5, "m"));
    checkRule(memory_size / memory_resolution <= 4096, section, "memory_size",
              numberText(memory_size),
              "more than 4096 memory cells a side (raise memory_resolution)");
    // a memory smaller than the local map, or of a few cells, remembers nothing
    checkRule(
        memory_size == 0 || memory_size >= local_map_size, section, "memory_size",
        numberText(memory_size),
        "must be 0 (none) or at least local_map_size = " + numberText(local_map_size));
    checkRule(memory_resolution <= local_map_size / 4, section, "memory_resolution",
              numberText(memory_resolution),
              "must be at most local_map_size / 4 = " + numberText(local_map_size / 4));
    checkKey(section, "sim_dt", sim_dt, TRange{0, 1, true, false, "s"});
    checkKey(section, "duration_max", duration_max, TRange{0, 36000, true, false, "s"});
    checkKey(section, "goal_tolerance", goal_tolerance, TRange{0, 10, true, false, "m"});
    checkKey(section, "arrival_radius", arrival_radius, TRange{0, 10, true, false, "m"});
    checkRule(arrival_radius <= goal_tolerance, section, "arrival_radius",
              numberText(arrival_radius),
              "must be at most goal_tolerance = " + numberText(goal_tolerance));
    checkKey(section, "unreachable_after", unreachable_after,
             TRange::closed(0, 3600, "s"));
    checkKey(section, "not_approaching_timeout", not_approaching_timeout,
             TRange::closed(0, 36000, "s"));
    checkKey(section, "max_snapshots", double(max_snapshots), TRange::closed(0, 1000));
}
}  // namespace risknav::speed
