#include <risknav/common/config_read.h>
#include <risknav/speed/TSpeedControlOptions.h>

using namespace risknav::common;

namespace risknav::speed {
void TSpeedControlOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                              const std::string& s) {
    section = s;
    speeds = readNumbers(c, s, "speeds", speeds);
    margins = readNumbers(c, s, "margins", margins);
    gap_threshold = readDouble(c, s, "gap_threshold", gap_threshold);
    cycle_time = readDouble(c, s, "cycle_time", cycle_time);
    lookahead_cycles = readInt(c, s, "lookahead_cycles", lookahead_cycles);
    occupied_threshold = readDouble(c, s, "occupied_threshold", occupied_threshold);
    free_threshold = readDouble(c, s, "free_threshold", free_threshold);
    frontier_goal_weight = readDouble(c, s, "frontier_goal_weight", frontier_goal_weight);
    target_switch_cost = readDouble(c, s, "target_switch_cost", target_switch_cost);
}

void TSpeedControlOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                            const std::string& s) const {
    writeKey(c, s, "speeds", speeds);
    writeKey(c, s, "margins", margins);
    writeKey(c, s, "gap_threshold", gap_threshold);
    writeKey(c, s, "cycle_time", cycle_time);
    writeKey(c, s, "lookahead_cycles", lookahead_cycles);
    writeKey(c, s, "occupied_threshold", occupied_threshold);
    writeKey(c, s, "free_threshold", free_threshold);
    writeKey(c, s, "frontier_goal_weight", frontier_goal_weight);
    writeKey(c, s, "target_switch_cost", target_switch_cost);
}

void TSpeedControlOptions::validate() const {
    checkRule(!speeds.empty() && speeds.size() <= 8, section, "speeds",
              std::to_string(speeds.size()) + " values", "needs 1 to 8 speeds");
    checkKey(section, "speeds", speeds, TRange{0, 10, true, false, "m/s"});
    checkKey(section, "margins", margins, TRange::closed(0, 5, "m"));
    checkRule(margins.size() == speeds.size(), section, "margins",
              std::to_string(margins.size()) + " values", "needs one margin per speed");
    for (size_t k = 1; k < speeds.size(); k++) {
        checkRule(speeds[k] < speeds[k - 1], section, "speeds", numberText(speeds[k]),
                  "must be sorted fastest first, without repeats");
        checkRule(margins[k] <= margins[k - 1], section, "margins",
                  numberText(margins[k]), "must not grow as the speed falls");
    }
    checkKey(section, "gap_threshold", gap_threshold, TRange{0, 100, true, false, "m"});
    checkKey(section, "cycle_time", cycle_time, TRange{0, 10, true, false, "s"});
    checkKey(section, "lookahead_cycles", double(lookahead_cycles),
             TRange::closed(0, 100));
    checkKey(section, "occupied_threshold", occupied_threshold,
             TRange{0.5, 1, false, true, ""});
    checkKey(section, "free_threshold", free_threshold, TRange{0, 0.5, true, true, ""});
    checkKey(section, "frontier_goal_weight", frontier_goal_weight,
             TRange::closed(1, 100));
    checkKey(section, "target_switch_cost", target_switch_cost,
             TRange::closed(0, 1000, "m"));
}
}  // namespace risknav::speed
