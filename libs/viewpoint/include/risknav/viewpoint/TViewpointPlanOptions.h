#pragma once
#include <mrpt/math/TPoint2D.h>
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/grid_io.h>
#include <risknav/mapping/TObstacleRule.h>
#include <risknav/viewpoint/observation_model.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace risknav::viewpoint {
/** [ViewpointPlan]: the world, the task and the planner's settings. Every
 * key is declared once, in declare(). */
struct TViewpointPlanOptions : public common::CDeclaredOptions {
    TViewpointPlanOptions() { section = "ViewpointPlan"; }
    std::string
        world_file;  ///< polygon world text (obstacles, bounds, landmarks); required
    /** Optional occupancy grid whose obstacles are traced into polygons and
     * added to the world file's (map_* keys as in every app, plus the
     * obstacle rule's keys and contour_tolerance). */
    common::TMapSourceOptions map;
    mapping::TObstacleRule rule;
    double contour_tolerance = 0.05;  ///< [m] polygon simplification of traced contours

    /** [m] x y, required (as risknav-risk-eval's start and goal) */
    mrpt::math::TPoint2D start{std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN()};
    mrpt::math::TPoint2D goal = start;  ///< [m] x y, required

    /** Safety margins S of the sweep [m] (004 Tables II/III: 10 ... 90 mm). */
    std::vector<double> safety_margins{0.01, 0.02, 0.03, 0.04, 0.05,
                                       0.06, 0.07, 0.08, 0.09};
    int k_paths = 10;              ///< paths per S (Yen's k shortest)
    int corner_segments = 16;      ///< corner polygons: a full turn in this many edges
    double sample_step = 0.02;     ///< [m] path samples = viewpoint candidates
    double dead_reckoning = 0.10;  ///< dead-reckoning error, fraction of the distance
    double start_error = 0;        ///< [m] position error at the start
    double start_heading_error_deg = 0;  ///< [deg] heading error at the start
    /** [m] ranking of feasible plans (bestPlan()): plans at most this much
     * longer than the shortest count as equally long, and then the fewer
     * viewpoints win (004's tables give lengths in mm: 0.001). */
    double length_tolerance = 0.001;
    bool exhaustive =
        false;        ///< evaluate every candidate (no pruning; same result, slower)
    int threads = 0;  ///< S values in parallel; 0: the machine's cores
    int monte_carlo_draws = 100;  ///< per viewpoint, checking every feasible plan's bound
    uint64_t seed = 1;            ///< of the Monte Carlo check

  protected:
    void declare(Visitor& v) override;
    void validateRules() const override;
};

/** [Camera]: the two panning cameras and their image errors. Every key is
 * declared once, in declare(). */
struct TCameraOptions : public common::CDeclaredOptions {
    TCameraOptions() { section = "Camera"; }
    double camera_offset = 0.1;     ///< [m] b_r, each camera's distance from the centre
    double focal_px = 3000;         ///< [px]
    int image_width = 640;          ///< [px]
    int image_height = 480;         ///< [px]
    double max_range = 5;           ///< [m] landmark distance limit
    double max_incidence_deg = 75;  ///< [deg] max angle off a landmark's facing
    double pan_limit_deg = 180;     ///< [deg] |pan| limit
    double du_px = 1, dv_px = 1,
           dr_px = 1;  ///< [px] image errors (004: R1 1 px, R2 3 px)

    TCameraRig rig() const;
    TImageErrors errors() const;

  protected:
    void declare(Visitor& v) override;
};

}  // namespace risknav::viewpoint
