#include <risknav/common/config_read.h>
#include <risknav/speed/TSpeedControlOptions.h>

using namespace risknav::common;

namespace risknav::speed {
void TSpeedControlOptions::declare(Visitor& v) {
    v.numbers(speeds, "speeds", TRange{0, 10, true, false, "m/s"},
              "candidates, fastest first, 1 to 8");
    v.numbers(margins, "margins", TRange::closed(0, 5, "m"),
              "motion-uncertainty margin per speed, not growing as the speed falls");
    v.number(gap_threshold, "gap_threshold", TRange{0, 100, true, false, "m"},
             "a jump in cost-to-go above this between consecutive speeds is a narrow "
             "passage");
    v.number(cycle_time, "cycle_time", TRange{0, 10, true, false, "s"},
             "T: one observation and one decision");
    v.integer(lookahead_cycles, "lookahead_cycles", TRange::closed(0, 100),
              "a faster speed must keep its margin this many cycles ahead");
    v.number(occupied_threshold, "occupied_threshold", TRange{0.5, 1, false, true, ""},
             "P > this: obstacle");
    v.number(free_threshold, "free_threshold", TRange{0, 0.5, true, true, ""},
             "P < this: free");
    v.number(frontier_goal_weight, "frontier_goal_weight", TRange::closed(1, 100),
             "a temporary destination minimises path to it + this x straight line "
             "to the goal");
    v.number(target_switch_cost, "target_switch_cost", TRange::closed(0, 1000, "m"),
             "added to a temporary destination more than 1 m from the previous one");
}

void TSpeedControlOptions::validateRules() const {
    checkRule(!speeds.empty() && speeds.size() <= 8, section, "speeds",
              std::to_string(speeds.size()) + " values", "needs 1 to 8 speeds");
    checkRule(margins.size() == speeds.size(), section, "margins",
              std::to_string(margins.size()) + " values", "needs one margin per speed");
    for (size_t k = 1; k < speeds.size(); k++) {
        checkRule(speeds[k] < speeds[k - 1], section, "speeds", numberText(speeds[k]),
                  "must be sorted fastest first, without repeats");
        checkRule(margins[k] <= margins[k - 1], section, "margins",
                  numberText(margins[k]), "must not grow as the speed falls");
    }
}
}  // namespace risknav::speed
