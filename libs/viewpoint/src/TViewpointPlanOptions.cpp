#include <risknav/common/config_read.h>
#include <risknav/viewpoint/TViewpointPlanOptions.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::viewpoint {
void TViewpointPlanOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                               const std::string& s) {
    section = s;
    world_file = readPath(c, s, "world_file", world_file, true);
    if (c.keyExists(s, "map_file"))
        map.loadFromConfigFile(c, s);
    rule.loadFromConfigFile(c, s);
    contour_tolerance = readDouble(c, s, "contour_tolerance", contour_tolerance);
    start = requirePoint(c, s, "start");
    goal = requirePoint(c, s, "goal");
    safety_margins = readNumbers(c, s, "safety_margins", safety_margins, {}, 1);
    k_paths = readInt(c, s, "k_paths", k_paths);
    corner_segments = readInt(c, s, "corner_segments", corner_segments);
    sample_step = readDouble(c, s, "sample_step", sample_step);
    dead_reckoning = readDouble(c, s, "dead_reckoning", dead_reckoning);
    start_error = readDouble(c, s, "start_error", start_error);
    start_heading_error_deg =
        readDouble(c, s, "start_heading_error_deg", start_heading_error_deg);
    length_tolerance = readDouble(c, s, "length_tolerance", length_tolerance);
    exhaustive = readBool(c, s, "exhaustive", exhaustive);
    threads = readInt(c, s, "threads", threads);
    monte_carlo_draws = readInt(c, s, "monte_carlo_draws", monte_carlo_draws);
    seed = uint64_t(readDouble(c, s, "seed", double(seed), TRange::closed(0, kMaxSeed)));
}

void TViewpointPlanOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                             const std::string& s) const {
    writeKey(c, s, "world_file", world_file);
    if (!map.map_file.empty()) {
        map.saveToConfigFile(c, s);
        rule.saveToConfigFile(c, s);
        writeKey(c, s, "contour_tolerance", contour_tolerance);
    }
    writeKey(c, s, "start", std::vector<double>{start.x, start.y});
    writeKey(c, s, "goal", std::vector<double>{goal.x, goal.y});
    writeKey(c, s, "safety_margins", safety_margins);
    writeKey(c, s, "k_paths", k_paths);
    writeKey(c, s, "corner_segments", corner_segments);
    writeKey(c, s, "sample_step", sample_step);
    writeKey(c, s, "dead_reckoning", dead_reckoning);
    writeKey(c, s, "start_error", start_error);
    writeKey(c, s, "start_heading_error_deg", start_heading_error_deg);
    writeKey(c, s, "length_tolerance", length_tolerance);
    writeKey(c, s, "exhaustive", exhaustive);
    writeKey(c, s, "threads", threads);
    writeKey(c, s, "monte_carlo_draws", monte_carlo_draws);
    writeKey(c, s, "seed", std::to_string(seed));
}

void TViewpointPlanOptions::validate() const {
    checkRule(!world_file.empty(), section, "world_file", world_file, "required");
    if (!map.map_file.empty()) {
        map.validate();
        rule.validate();
    }
    checkKey(section, "contour_tolerance", contour_tolerance, TRange::closed(0, 1, "m"));
    for (const auto& [key, p] :
         {std::make_pair("start", start), std::make_pair("goal", goal)})
        checkRule(std::isfinite(p.x) && std::isfinite(p.y) && std::abs(p.x) <= 1e5 &&
                      std::abs(p.y) <= 1e5,
                  section, key, numberText(p.x) + " " + numberText(p.y),
                  "required, as x y in [-1e5 .. 1e5] m");
    checkRule(std::hypot(goal.x - start.x, goal.y - start.y) > 1e-6, section, "goal",
              numberText(goal.x) + " " + numberText(goal.y),
              "the goal must differ from the start");
    checkRule(!safety_margins.empty() && safety_margins.size() <= 100, section,
              "safety_margins", std::to_string(safety_margins.size()) + " values",
              "1 to 100 values");
    checkKey(section, "safety_margins", safety_margins, TRange::closed(0.001, 10, "m"));
    for (size_t i = 0; i < safety_margins.size(); i++)
        for (size_t j = 0; j < i; j++)
            checkRule(safety_margins[i] != safety_margins[j], section, "safety_margins",
                      numberText(safety_margins[i]), "each margin at most once");
    checkKey(section, "k_paths", k_paths, TRange::closed(1, 100));
    checkKey(section, "corner_segments", corner_segments, TRange::closed(4, 360));
    checkKey(section, "sample_step", sample_step, TRange::closed(0.001, 1, "m"));
    checkKey(section, "dead_reckoning", dead_reckoning,
             TRange::closed(0, 1, "(fraction)"));
    checkKey(section, "start_error", start_error, TRange::closed(0, 100, "m"));
    checkKey(section, "start_heading_error_deg", start_heading_error_deg,
             TRange::closed(0, 180, "deg"));
    checkKey(section, "length_tolerance", length_tolerance, TRange::closed(0, 1000, "m"));
    checkKey(section, "threads", threads, TRange::closed(0, 64));
    checkKey(section, "monte_carlo_draws", monte_carlo_draws, TRange::closed(0, 100000));
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
