#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <mrpt/math/TPose2D.h>

#include <cstdint>
#include <string>
#include <vector>

namespace risknav::nav {
/** [Navigate]: one closed-loop run of risknav-navigate (keys documented in
 * config/risknav-navigate.ini). The route is one of: `goals` (points),
 * `route_file` (an MRPT TWaypointSequence file, e.g. risknav-viewpoint-plan's
 * waypoints.ini) or `risk_config` (risknav-risk-eval's config: the route of
 * the lowest U, or the one `risk_route` names). */
struct TNavigateOptions : public common::CDeclaredOptions {
    TNavigateOptions() { section = "Navigate"; }
    mrpt::math::TPose2D start;        ///< start x [m], y [m], heading (radians in code)
    std::vector<double> goals;        ///< x0 y0 x1 y1 ... [m]
    std::string route_file;           ///< MRPT waypoints ini ([Waypoints])
    std::string risk_config;          ///< risknav-risk-eval config
    std::string risk_route = "best";  ///< best | worst | a route name
    double goal_tolerance = 0.3;      ///< [m] allowed distance to each waypoint
    /** [m] MRPT's engine is asked to come within min(this, the last
     * waypoint's allowed distance) of the route's end on the believed pose;
     * the run is judged on the true pose against the allowed distance. Below
     * the tolerance so that a belief off by up to the difference (MCL: a few
     * cm) still ends truly within it, as risknav-explore's arrival_radius.
     * A goal nearer an obstacle than MRPT's disc is asked within the
     * nearest the disc lets the centre come (+ 0.1 m) instead. */
    double arrival_radius = 0.15;
    std::string mode = "once";                  ///< once | back_and_forth | loop
    int laps = 1;                               ///< passes of the route (mode != once)
    std::string localization = "ground_truth";  ///< ground_truth | odometry | mcl
    /** localization = odometry: sigmas x [m], y [m], heading (radians in code)
     * of the belief's error at the start, drawn once per seed (0 0 0 = the
     * start is known exactly). risknav-risk-eval's init_sigma_* assume the
     * robot starts with such an error. */
    std::vector<double> start_sigma{0.0, 0.0, 0.0};
    double sim_dt = 0.05;       ///< [s] physics step
    double nav_period = 0.2;    ///< [s] one navigation cycle (and rawlog frame)
    double duration_max = 600;  ///< [s] simulated; then status "timeout"
    /** [s] the robot staying within stall_distance of one spot this long
     * while navigating, its target not under it (within its radius + the
     * target's allowed distance), ends the run, status "stalled" (0 = never). Beyond
     * MRPT: its "not approaching" alarm watches the distance to the target,
     * which a robot creeping at 1e-4 m/s against an edge keeps lowering, so
     * it never fires. 120 s: MRPT's engine got out of such creeps after 30 s
     * and 81 s (validation/u_corridor, M1), but not after 370 s (hall). */
    double stall_timeout = 120;
    double stall_distance = 0.1;  ///< [m]
    uint64_t seed = 1;
    double start_time = 1.6e9;        ///< [s] UNIX time of t = 0
    double near_miss_distance = 0.2;  ///< [m]
    /** [m] MRPT's engine plans for a disc of the robot's radius + this (its
     * paths then keep this clearance, which the limiters' swept corridors
     * also ask for). */
    double shape_margin = 0.1;
    bool navlog = true;  ///< write the .reactivenavlog
    bool rawlog = true;  ///< write the run's rawlog
    /** An MRPT reactive-navigation config for the engine's sections ("" = they
     * are in this file); keys of this file override it. */
    std::string engine_config;
    std::string ptg_cache_dir;  ///< MRPT's PTG grid cache ("" = system temp)
    /** grid: every waypoint is reached along a global plan on the known map
     * (CGlobalPlanner, [GlobalPlanner]); risk: the same, the way to each
     * waypoint chosen by M2's U among ways of distinct homotopy classes
     * (CRiskRouteChooser); none: MRPT's engine aims straight
     * at each waypoint (the papers' experiments, and a world the robot
     * does not know: CAdaptiveSpeedLimiter plans on its own map). */
    std::string global_planner = "grid";

  protected:
    void declare(Visitor& v) override;
    /** One route source, risk_route and start_sigma only where they apply,
     * start_sigma's parts, nav_period a multiple of sim_dt, the run's work
     * bounded. */
    void validateRules() const override;
};

}  // namespace risknav::nav
