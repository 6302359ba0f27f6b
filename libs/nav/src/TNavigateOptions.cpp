#include <risknav/common/config_read.h>
#include <risknav/nav/TNavigateOptions.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::nav {
namespace {
const char* kSec = "Navigate";

// An optional file key: absent is fine, named means it must exist.
std::string optionalFile(const mrpt::config::CConfigFileBase& c, const std::string& s,
                         const std::string& k, const std::string& def) {
    return readString(c, s, k, def).empty() ? def : readPath(c, s, k, def, true);
}
}  // namespace

void TNavigateOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                          const std::string& s) {
    const auto st = readNumbers(c, s, "start", {}, {}, 0);
    if (!st.empty()) {
        if (st.size() != 3)
            throwBadKey(c, s, "start", readString(c, s, "start", ""),
                        "expected x [m] y [m] heading [deg]");
        // the heading in degrees as typed (in radians it could overflow, and
        // MRPT's obstacle filter crashed on an inf heading)
        if (!(std::abs(st[2]) <= 3600))
            throwBadKey(c, s, "start", readString(c, s, "start", ""),
                        "the heading must be in [-3600, 3600] deg");
        start = mrpt::math::TPose2D(st[0], st[1], st[2] * M_PI / 180.0);
    } else
        throw CBadInputError(configWhere(c, s, "start") + "[" + s +
                             "] start: required key is missing (x y heading_deg)");
    goals = readNumbers(c, s, "goals", goals, {}, 0, 2);
    route_file = optionalFile(c, s, "route_file", route_file);
    risk_config = optionalFile(c, s, "risk_config", risk_config);
    risk_route = readString(c, s, "risk_route", risk_route);
    goal_tolerance = readDouble(c, s, "goal_tolerance", goal_tolerance);
    arrival_radius = readDouble(c, s, "arrival_radius", arrival_radius);
    mode = readChoice(c, s, "mode", mode, {"once", "back_and_forth", "loop"});
    laps = readInt(c, s, "laps", laps);
    localization = readChoice(c, s, "localization", localization,
                              {"ground_truth", "odometry", "mcl"});
    {
        const auto ss = readNumbers(c, s, "start_sigma", {}, {}, 0);
        if (!ss.empty()) {
            if (ss.size() != 3)
                throwBadKey(c, s, "start_sigma", readString(c, s, "start_sigma", ""),
                            "expected sigma_x [m] sigma_y [m] sigma_heading [deg]");
            start_sigma = {ss[0], ss[1], ss[2] * M_PI / 180.0};
        }
    }
    sim_dt = readDouble(c, s, "sim_dt", sim_dt);
    nav_period = readDouble(c, s, "nav_period", nav_period);
    duration_max = readDouble(c, s, "duration_max", duration_max);
    stall_timeout = readDouble(c, s, "stall_timeout", stall_timeout);
    stall_distance = readDouble(c, s, "stall_distance", stall_distance);
    const double sd = readDouble(c, s, "seed", double(seed), TRange::closed(0, kMaxSeed));
    if (sd != std::floor(sd))
        throwBadKey(c, s, "seed", readString(c, s, "seed", ""), "not an integer");
    seed = static_cast<uint64_t>(sd);
    start_time = readDouble(c, s, "start_time", start_time);
    near_miss_distance = readDouble(c, s, "near_miss_distance", near_miss_distance);
    shape_margin = readDouble(c, s, "shape_margin", shape_margin);
    navlog = readBool(c, s, "navlog", navlog);
    rawlog = readBool(c, s, "rawlog", rawlog);
    engine_config = optionalFile(c, s, "engine_config", engine_config);
    ptg_cache_dir = readPath(c, s, "ptg_cache_dir", ptg_cache_dir, false);
    global_planner =
        readChoice(c, s, "global_planner", global_planner, {"grid", "risk", "none"});
}

void TNavigateOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                        const std::string& s) const {
    writeKey(c, s, "start",
             std::vector<double>{start.x, start.y, start.phi * 180.0 / M_PI});
    writeKey(c, s, "goals", goals);
    writeKey(c, s, "route_file", route_file);
    writeKey(c, s, "risk_config", risk_config);
    writeKey(c, s, "risk_route", risk_route);
    writeKey(c, s, "goal_tolerance", goal_tolerance);
    writeKey(c, s, "arrival_radius", arrival_radius);
    writeKey(c, s, "mode", mode);
    writeKey(c, s, "laps", laps);
    writeKey(c, s, "localization", localization);
    writeKey(c, s, "start_sigma",
             std::vector<double>{start_sigma[0], start_sigma[1],
                                 start_sigma[2] * 180.0 / M_PI});
    writeKey(c, s, "sim_dt", sim_dt);
    writeKey(c, s, "nav_period", nav_period);
    writeKey(c, s, "duration_max", duration_max);
    writeKey(c, s, "stall_timeout", stall_timeout);
    writeKey(c, s, "stall_distance", stall_distance);
    writeKey(c, s, "seed", std::to_string(seed));
    writeKey(c, s, "start_time", start_time);
    writeKey(c, s, "near_miss_distance", near_miss_distance);
    writeKey(c, s, "shape_margin", shape_margin);
    writeKey(c, s, "navlog", navlog);
    writeKey(c, s, "rawlog", rawlog);
    writeKey(c, s, "engine_config", engine_config);
    writeKey(c, s, "ptg_cache_dir", ptg_cache_dir);
    writeKey(c, s, "global_planner", global_planner);
}

void TNavigateOptions::validate() const {
    const std::string s = kSec;
    checkKey(s, "start", std::vector<double>{start.x, start.y},
             TRange::closed(-1e5, 1e5, "m"));
    checkKey(s, "goals", goals, TRange::closed(-1e5, 1e5, "m"));
    checkRule(goals.size() <= 2 * 10000, s, "goals",
              std::to_string(goals.size() / 2) + " points", "at most 10000 points");
    const int sources =
        int(!goals.empty()) + int(!route_file.empty()) + int(!risk_config.empty());
    checkRule(sources == 1, s, "goals", std::to_string(sources) + " route sources",
              "give exactly one of goals, route_file, risk_config");
    checkRule(!risk_route.empty(), s, "risk_route", risk_route,
              "best, worst or a route name");
    // (like start_sigma below: a setting that would be ignored is an error)
    checkRule(risk_route == "best" || !risk_config.empty(), s, "risk_route", risk_route,
              "only with risk_config (the risk evaluator's routes)");
    checkKey(s, "goal_tolerance", goal_tolerance, TRange::closed(0.05, 10, "m"));
    checkKey(s, "arrival_radius", arrival_radius, TRange::closed(0.01, 10, "m"));
    checkKey(s, "laps", laps, TRange::closed(1, 1000, "laps"));
    checkKey(s, "start_sigma", std::vector<double>{start_sigma[0], start_sigma[1]},
             TRange::closed(0, 10, "m"));
    checkDegrees(s, "start_sigma", start_sigma[2], TRange::closed(0, 90, "deg"));
    checkRule(localization == "odometry" ||
                  (start_sigma[0] == 0 && start_sigma[1] == 0 && start_sigma[2] == 0),
              s, "start_sigma",
              numberText(start_sigma[0]) + " " + numberText(start_sigma[1]) + " " +
                  numberText(start_sigma[2] * 180 / M_PI),
              "only with localization = odometry (here " + localization + ")");
    checkKey(s, "sim_dt", sim_dt, TRange::closed(0.001, 0.5, "s"));
    checkKey(s, "nav_period", nav_period, TRange::closed(0.01, 2, "s"));
    const double ratio = nav_period / sim_dt;
    checkRule(std::abs(ratio - std::round(ratio)) <= 1e-6, s, "nav_period",
              numberText(nav_period), "must be a whole multiple of sim_dt");
    checkKey(s, "duration_max", duration_max, TRange::closed(1, 1e5, "s"));
    // The run's work, bounded before it starts (1e5 s at the default 0.05 s
    // and 0.2 s; sim_dt 0.001 over 1e5 s would be 1e8 world steps, hours)
    checkRule(duration_max / sim_dt <= 2e6 * (1 + 1e-9), s, "duration_max",
              numberText(duration_max),
              "is " + numberText(std::round(duration_max / sim_dt)) +
                  " world steps of sim_dt = " + numberText(sim_dt) +
                  " s, at most 2e+06 (lower duration_max or raise sim_dt)");
    checkRule(duration_max / nav_period <= 5e5 * (1 + 1e-9), s, "duration_max",
              numberText(duration_max),
              "is " + numberText(std::round(duration_max / nav_period)) +
                  " navigation cycles of nav_period = " + numberText(nav_period) +
                  " s, at most 5e+05 (lower duration_max or raise nav_period)");
    checkKey(s, "stall_timeout", stall_timeout, TRange::closed(0, 1e5, "s"));
    checkKey(s, "stall_distance", stall_distance, TRange::closed(0.001, 10, "m"));
    checkKey(s, "start_time", start_time, TRange::closed(0, 4e9, "s"));
    checkKey(s, "near_miss_distance", near_miss_distance, TRange::closed(0, 5, "m"));
    checkKey(s, "shape_margin", shape_margin, TRange::closed(0, 2, "m"));
}

}  // namespace risknav::nav
