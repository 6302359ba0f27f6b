#pragma once
#include <risknav/common/parallel_for.h>
#include <risknav/mapping/free_space.h>

#include <limits>
#include <vector>

namespace risknav::speed {
/** What the planners and the speed rules read from one cycle's free-space
 * map: per cell the clearance [m] to the nearest non-free cell (obstacle or
 * undecided; the ring outside the grid counts as non-free). Exact Euclidean
 * distances (mapping::squaredDistanceTransform) from the cell's centre to the other
 * cell's near edge (centre distance - half a cell). A frontier cell is an
 * undecided cell 4-adjacent to a free cell: where the unknown begins
 * (undecided cells walled off behind obstacles are none).
 * For the choice of a temporary destination only (beyond the paper),
 * `wayOnDist()` is the distance to the ways on: the frontier cells where the
 * unknown could let the robot on, at least `minOpening` from every obstacle
 * cell (a hole of a few undecided cells in a wall, which noise leaves
 * undecided however often it is observed, is a frontier for the undecided
 * rule but no way on), and the free cells of the grid's outer ring, as far
 * from obstacles (where the map ends, not the world: the way on back along a
 * corridor the robot-centred grid has forgotten).
 * `wayOnDist()` is exact up to `wayOnReach`; beyond it a cell may hold +inf
 * (the controller only asks whether a cell is within a band of the ways on,
 * so the pipeline computes no farther: a speed-up, the same decisions).
 * Likewise `clearance` is exact up to `clearanceReach` and may hold +inf
 * beyond it: every reader compares it with a bound (an inflation, the robot
 * radius) that the pipeline keeps below the reach; the one comparison of two
 * clearances (lookaheadPoint()'s chord against the path) then accepts a chord
 * that stays beyond the reach (a speed-up beyond the paper: the bounded
 * transform takes about a third of the exact one's time on the local map). */
struct TPlanningField {
    mapping::TFreeSpaceMap map;
    std::vector<float> clearance;  ///< [m], 0 on non-free cells
    double wayOnReach = std::numeric_limits<double>::infinity();      ///< [m]
    double clearanceReach = std::numeric_limits<double>::infinity();  ///< [m]
    double minOpening = 0;  ///< [m] of the ways on (see wayOnDist())
    double clearanceAt(double x, double y) const;
    /** [m] per cell, to open frontier and map-edge cells. Only the choice of
     * a temporary destination reads it, which a goal the slowest speed
     * reaches does not need (most cycles of a navigation between known
     * places): unless computePlanningField() made it, it is computed at
     * the first call (a speed-up beyond the paper, the same values). Not
     * for first calls from two threads at once. */
    const std::vector<float>& wayOnDist() const;
    /** Whether wayOnDist() is computed already. */
    bool hasWayOnDist() const { return m_wayOnReady; }

  private:
    mutable std::vector<float> m_wayOnDist;
    mutable bool m_wayOnReady = false;
};

/** `minOpening` [m]: see wayOnDist (0: every frontier cell is open);
 * `wayOnReach` [m]: wayOnDist is exact up to it (+inf: everywhere);
 * `clearanceReach` [m]: clearance is exact up to it (+inf: everywhere);
 * `parallel`: how the clearance and the ways on (independent) are computed
 * (empty: one after the other; the same field either way); `wayOnNow`:
 * the ways on now (beside the clearance), else at the first wayOnDist(). */
TPlanningField computePlanningField(
    const mapping::TFreeSpaceMap& map, double minOpening = 0.0,
    double wayOnReach = std::numeric_limits<double>::infinity(),
    double clearanceReach = std::numeric_limits<double>::infinity(),
    const common::TParallelFor& parallel = {}, bool wayOnNow = true);
}  // namespace risknav::speed
