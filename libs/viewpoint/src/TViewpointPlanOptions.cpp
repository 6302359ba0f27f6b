#include <risknav/common/config_read.h>
#include <risknav/viewpoint/TViewpointPlanOptions.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::viewpoint {
void TViewpointPlanOptions::declare(Visitor& v) {
    v.path(world_file, "world_file", true,
           "polygon world (obstacles, bounds, landmarks); required");
    // the occupancy grid is optional: its keys (map_*, the obstacle rule) are
    // read only with map_file, and saved and checked only when it is given
    const bool mapGiven = !map.map_file.empty();
    v.includeIfGiven(map, "map_file", mapGiven);
    v.includeIfGiven(rule, "map_file", mapGiven);
    v.number(contour_tolerance, "contour_tolerance", TRange::closed(0, 1, "m"),
             "polygon simplification of the map's traced contours");
    const TRange xy = TRange::closed(-1e5, 1e5, "m");
    v.point(start, "start", xy, "x y [m]");
    v.point(goal, "goal", xy, "x y [m]");
    v.numbers(safety_margins, "safety_margins", TRange::closed(0.001, 10, "m"),
              "the sweep's safety margins S, 1 to 100, each once",
              TCount{1, 1, 0, false});
    v.integer(k_paths, "k_paths", TRange::closed(1, 100),
              "paths per S (Yen's k shortest)");
    v.integer(corner_segments, "corner_segments", TRange::closed(4, 360),
              "edges of a full turn of the corner polygons");
    v.number(sample_step, "sample_step", TRange::closed(0.001, 1, "m"),
             "path samples = viewpoint candidates");
    v.number(dead_reckoning, "dead_reckoning", TRange::closed(0, 1, "(fraction)"),
             "dead-reckoning error, fraction of the distance");
    v.number(start_error, "start_error", TRange::closed(0, 100, "m"),
             "position error bound at the start");
    v.number(start_heading_error_deg, "start_heading_error_deg",
             TRange::closed(0, 180, "deg"), "heading error bound at the start");
    v.number(length_tolerance, "length_tolerance", TRange::closed(0, 1000, "m"),
             "plans within this of the shortest count as equally long");
    v.flag(exhaustive, "exhaustive", "evaluate every candidate (no pruning)");
    v.integer(threads, "threads", TRange::closed(0, 64),
              "S values in parallel; 0: the machine's cores");
    v.integer(monte_carlo_draws, "monte_carlo_draws", TRange::closed(0, 100000),
              "per viewpoint, checking every feasible plan's bound");
    v.seed(seed, "seed", "of the Monte Carlo check (--seed overrides)");
}

void TViewpointPlanOptions::validateRules() const {
    checkRule(!world_file.empty(), section, "world_file", world_file, "required");
    checkRule(std::hypot(goal.x - start.x, goal.y - start.y) > 1e-6, section, "goal",
              numberText(goal.x) + " " + numberText(goal.y),
              "the goal must differ from the start");
    checkRule(safety_margins.size() <= 100, section, "safety_margins",
              std::to_string(safety_margins.size()) + " values", "1 to 100 values");
    for (size_t i = 0; i < safety_margins.size(); i++)
        for (size_t j = 0; j < i; j++)
            checkRule(safety_margins[i] != safety_margins[j], section, "safety_margins",
                      numberText(safety_margins[i]), "each margin at most once");
}

TCameraRig TCameraOptions::rig() const {
    TCameraRig r;
    r.b_r = camera_offset;
    r.focal = focal_px;
    r.width = image_width;
    r.height = image_height;
    r.maxRange = max_range;
    r.maxIncidence = max_incidence_deg * M_PI / 180;
    r.panLimit = pan_limit_deg * M_PI / 180;
    return r;
}

TImageErrors TCameraOptions::errors() const {
    return {du_px, dv_px, dr_px};
}

void TCameraOptions::declare(Visitor& v) {
    v.number(camera_offset, "camera_offset", TRange::closed(0.001, 10, "m"),
             "b_r: each camera's distance from the robot centre");
    v.number(focal_px, "focal_px", TRange::closed(1, 1e6, "px"), "focal length");
    v.integer(image_width, "image_width", TRange::closed(8, 100000, "px"), "image width");
    v.integer(image_height, "image_height", TRange::closed(8, 100000, "px"),
              "image height");
    v.number(max_range, "max_range", TRange::closed(0.01, 1000, "m"),
             "landmarks farther away are not seen");
    v.number(max_incidence_deg, "max_incidence_deg", TRange::closed(0, 89.9, "deg"),
             "landmarks seen more obliquely than this off their facing are not seen");
    v.number(pan_limit_deg, "pan_limit_deg", TRange::closed(0, 180, "deg"),
             "each camera pans within +-this of the robot's heading");
    v.number(du_px, "du_px", TRange::closed(0, 1000, "px"),
             "error of a landmark's image centre, horizontal");
    v.number(dv_px, "dv_px", TRange::closed(0, 1000, "px"), "the same, vertical");
    v.number(dr_px, "dr_px", TRange::closed(0, 1000, "px"),
             "error of a landmark's apparent radius");
}

}  // namespace risknav::viewpoint
