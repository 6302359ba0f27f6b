#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <string>
#include <vector>

namespace risknav::speed {
/** [SpeedControl]: the adaptive speed controller of Miura et al. 2006 (000),
 * PAPER_NOTES M1. Every key is declared once, in declare(). */
struct TSpeedControlOptions : public common::CDeclaredOptions {
    TSpeedControlOptions() { section = "SpeedControl"; }
    /** Candidate speeds [m/s], fastest first, and the motion-uncertainty
     * margin of each [m] ((000) section 6: 1.1 / 0.7 / 0.35 / 0.2 m/s with
     * 30 / 20 / 10 / 5 cm). The robot-size margin (its radius) comes on top. */
    std::vector<double> speeds = {1.1, 0.7, 0.35, 0.2};
    std::vector<double> margins = {0.30, 0.20, 0.10, 0.05};
    /** [m] a jump in cost-to-go between consecutive speeds above this is a
     * narrow passage (section 4.1). */
    double gap_threshold = 1.0;
    double cycle_time = 0.3;  ///< T [s], one observation and one decision
    int lookahead_cycles =
        2;  ///< section 4.2: a faster speed must keep its margin this long
    double occupied_threshold = 0.7;  ///< section 2 classification
    double free_threshold = 0.2;
    /** Beyond the paper: a temporary destination minimises path length to it
     * + this x straight-line distance from it to the goal (the unknown part
     * of the way counts more than the known part; a very large weight gives
     * the paper's rule, the boundary point nearest the goal). */
    double frontier_goal_weight = 2.0;
    /** [m] Beyond the paper: added to the cost of a temporary destination
     * more than 1 m from the previous cycle's (hysteresis; see TTargetHints). */
    double target_switch_cost = 3.0;

  protected:
    void declare(Visitor& v) override;
    /** 1 to 8 speeds strictly decreasing, one margin per speed and not
     * increasing (a slower speed cannot need a larger margin). */
    void validateRules() const override;
};
}  // namespace risknav::speed
