#include <risknav/common/config_read.h>
#include <risknav/nav/TNavigateOptions.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::nav {
void TNavigateOptions::declare(Visitor& v) {
    // the heading in degrees as typed (in radians it could overflow, and
    // MRPT's obstacle filter crashed on an inf heading)
    v.pose(start, "start", TRange::closed(-1e5, 1e5, "m"),
           TRange::closed(-3600, 3600, "deg"), "x y heading_deg");
    v.numbers(goals, "goals", TRange::closed(-1e5, 1e5, "m"), "x y pairs: MRPT waypoints",
              TCount{0, 2});
    v.path(route_file, "route_file", true, "an MRPT waypoints file ([Waypoints])");
    v.path(risk_config, "risk_config", true, "risknav-risk-eval's config: its routes");
    v.text(risk_route, "risk_route", false, "best | worst | a route name (risk_config)");
    v.number(goal_tolerance, "goal_tolerance", TRange::closed(0.05, 10, "m"),
             "allowed distance to each waypoint");
    v.number(arrival_radius, "arrival_radius", TRange::closed(0.01, 10, "m"),
             "MRPT is asked to come within min(this, the allowed distance)");
    v.choice(mode, "mode", {"once", "back_and_forth", "loop"},
             "how laps repeat the route");
    v.integer(laps, "laps", TRange::closed(1, 1000, "laps"),
              "passes of the route (mode != once)");
    v.choice(localization, "localization", {"ground_truth", "odometry", "mcl"},
             "the pose the navigator believes");
    // sigmas x [m], y [m] and the heading in degrees in the file (radians
    // held); each part's range is a rule below (two units in one list)
    std::vector<double> sigma{start_sigma[0], start_sigma[1],
                              start_sigma[2] * 180.0 / M_PI};
    const auto sigmaBuilt = sigma;
    v.numbers(sigma, "start_sigma", TRange::any(),
              "sigma x [m] y [m] heading [deg] of the start belief (0-10 m, 0-90 deg)",
              TCount{0, 1, 3});
    if (sigma != sigmaBuilt)
        start_sigma = {sigma[0], sigma[1], sigma[2] * M_PI / 180.0};
    v.number(sim_dt, "sim_dt", TRange::closed(0.001, 0.5, "s"), "physics step");
    v.number(nav_period, "nav_period", TRange::closed(0.01, 2, "s"),
             "one navigation cycle and rawlog frame (a multiple of sim_dt)");
    v.number(duration_max, "duration_max", TRange::closed(1, 1e5, "s"),
             "simulated; then status \"timeout\"");
    v.number(stall_timeout, "stall_timeout", TRange::closed(0, 1e5, "s"),
             "within stall_distance of one spot this long: \"stalled\" (0 = never)");
    v.number(stall_distance, "stall_distance", TRange::closed(0.001, 10, "m"),
             "the spot's radius for stall_timeout");
    v.seed(seed, "seed", "people, sensor noise, odometry errors (--seed overrides)");
    v.number(start_time, "start_time", TRange::closed(0, 4e9, "s"),
             "UNIX time of t = 0 (the logs' timestamps)");
    v.number(near_miss_distance, "near_miss_distance", TRange::closed(0, 5, "m"),
             "robot edge to object edge below which a pass is a near miss");
    v.number(shape_margin, "shape_margin", TRange::closed(0, 2, "m"),
             "MRPT plans for a disc of [Robot] radius + this");
    v.flag(navlog, "navlog", "write navigation.reactivenavlog");
    v.flag(rawlog, "rawlog", "write navigation.rawlog and groundtruth.txt");
    v.path(engine_config, "engine_config", true,
           "MRPT's reactive-navigation config ('' = its sections are here)");
    v.path(ptg_cache_dir, "ptg_cache_dir", false,
           "MRPT's PTG grid cache ('' = the system's temp folder)");
    v.choice(global_planner, "global_planner", {"grid", "risk", "none"},
             "how each waypoint is reached");
}

void TNavigateOptions::validateRules() const {
    const std::string& s = section;
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
    checkKey(s, "start_sigma", std::vector<double>{start_sigma[0], start_sigma[1]},
             TRange::closed(0, 10, "m"));
    checkDegrees(s, "start_sigma", start_sigma[2], TRange::closed(0, 90, "deg"));
    checkRule(localization == "odometry" ||
                  (start_sigma[0] == 0 && start_sigma[1] == 0 && start_sigma[2] == 0),
              s, "start_sigma",
              numberText(start_sigma[0]) + " " + numberText(start_sigma[1]) + " " +
                  numberText(start_sigma[2] * 180 / M_PI),
              "only with localization = odometry (here " + localization + ")");
    const double ratio = nav_period / sim_dt;
    checkRule(std::abs(ratio - std::round(ratio)) <= 1e-6, s, "nav_period",
              numberText(nav_period), "must be a whole multiple of sim_dt");
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
}

}  // namespace risknav::nav
