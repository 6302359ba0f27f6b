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
 * (centre distance - half a cell). */
struct TPlanningField {
    mapping::TFreeSpaceMap map;
    std::vector<float> clearance;     ///< [m], 0 on non-free cells
    std::vector<float> frontierDist;  ///< [m], +inf when there is no frontier
    double clearanceAt(double x, double y) const;
    double frontierDistAt(double x, double y) const;
};

TPlanningField computePlanningField(const mapping::TFreeSpaceMap& map);
}  // namespace risknav::speed
