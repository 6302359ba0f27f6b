#pragma once
#include <risknav/mapping/free_space.h>

#include <vector>

namespace risknav::speed {
/** What the planners and the speed rules read from one cycle's free-space
 * map: per cell the clearance [m] to the nearest non-free cell (obstacle or
 * undecided; the ring outside the grid counts as non-free) and the distance
 * [m] to the nearest frontier cell (an undecided cell 4-adjacent to a free
 * cell: where the unknown begins; undecided cells walled off behind
 * obstacles are not a frontier). Exact Euclidean distances (OpenCV's
 * distance transform) from the cell's centre to the other cell's near edge
 * (centre distance - half a cell).
 * For the choice of a temporary destination only, `openFrontierDist` keeps
 * the frontier cells where the unknown could let the robot on: at least
 * `minOpening` from every obstacle cell (beyond the paper: a hole of a few
 * undecided cells in a wall, which noise leaves undecided however often it
 * is observed, is a frontier for the undecided rule but no way on).
 * `borderDist`: to the free cells of the grid's outer ring at least
 * `minOpening` from every obstacle (where the map ends, not the world: the
 * way on when no open frontier is left, e.g. back along a corridor the
 * robot-centred grid has forgotten). */
struct TPlanningField {
    mapping::TFreeSpaceMap map;
    std::vector<float> clearance;         ///< [m], 0 on non-free cells
    std::vector<float> frontierDist;      ///< [m], +inf when there is no frontier
    std::vector<float> openFrontierDist;  ///< [m], to open frontier cells only
    std::vector<float> borderDist;        ///< [m], to open cells on the grid's edge
    double clearanceAt(double x, double y) const;
    double frontierDistAt(double x, double y) const;
};

/** `minOpening` [m]: see openFrontierDist (0: every frontier cell is open). */
TPlanningField computePlanningField(const mapping::TFreeSpaceMap& map,
                                    double minOpening = 0.0);
}  // namespace risknav::speed
