#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <string>

namespace risknav::mapping {
/** Which cells of an occupancy grid are obstacles: the one rule that the
 * simulator (its collisions and what its range sensors echo on), the risk
 * evaluator and the afraid learner share. MRPT cells hold
 * P(free); occupancy = 1 - P(free). A cell is
 *  - an obstacle if occupancy >= occupied_threshold,
 *  - free if occupancy <= free_threshold,
 *  - unknown otherwise (MRPT's 0.5 of never-seen cells, grey map pixels), an
 *    obstacle when unknown_is_obstacle.
 * Cells outside the map are obstacles when outside_is_obstacle (a map without
 * a border wall then still bounds the robot). The keys live in the section
 * that names the map (e.g. [World], [RiskEval], [AfraidLearn]). Every key,
 * its range and its doc are declared once, in declare(). */
struct TObstacleRule : public common::CDeclaredOptions {
    TObstacleRule() { section = "World"; }
    double occupied_threshold = 0.65;  ///< occupancy >= this: obstacle
    double free_threshold = 0.35;      ///< occupancy <= this: free; between: unknown
    bool unknown_is_obstacle = true;
    bool outside_is_obstacle = true;

    /** The rule for one cell value (MRPT's P(free) in [0, 1]): the one
     * function that makes a cell a wall for the collisions, the clearances
     * and the simulated range sensors alike. */
    bool isObstacle(float pFree) const {
        const double occ = 1.0 - double(pFree);
        return occ >= occupied_threshold || (unknown_is_obstacle && occ > free_threshold);
    }

  protected:
    void declare(Visitor& v) override;
    /** free_threshold < occupied_threshold. */
    void validateRules() const override;
};

}  // namespace risknav::mapping
