#pragma once
#include <cstdint>
#include <limits>
#include <vector>

namespace risknav::planning {
/** A grid of traversal costs for the global planner: per cell a cost per
 * metre >= 1 (+inf: the robot may not be there), row-major w x h, square
 * cells of `resolution` [m]. */
struct TCostGrid {
    int w = 0, h = 0;
    double resolution = 0.05;
    std::vector<float> cost;
    size_t index(int x, int y) const { return size_t(y) * size_t(w) + size_t(x); }
    bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
    bool passable(size_t i) const {
        return cost[i] < std::numeric_limits<float>::infinity();
    }
};

/** A least-cost path between two cells. */
struct TGridPath {
    std::vector<int32_t> cells;  ///< cell indices, start first; empty: none
    double cost = std::numeric_limits<double>::infinity();  ///< [m x cost]
    size_t expanded = 0;  ///< cells the search closed (its work)
};

/** A* on the 8-connected cells (Hart, Nilsson & Raphael 1968): a move
 * between adjacent cells a, b costs its length times the mean of their
 * costs; a diagonal move needs both cells beside it passable (no squeezing
 * between two blocked corners). The heuristic is the octile distance, a
 * lower bound because every cost is >= 1, and consistent, so the first time
 * the goal is closed its cost is the least (optimal, as a Dijkstra over the
 * same graph: tests/unit/nav check it against Bellman-Ford). Start or goal
 * outside or not passable: no path. Reuses its buffers per thread. */
TGridPath gridAStar(const TCostGrid& g, int32_t start, int32_t goal);

/** The widest way: the largest c such that a 4-connected chain of cells
 * with clearance[] >= c joins start and goal (a bottleneck search, Dijkstra
 * with max-min), 0 when even cells of clearance > 0 do not join them;
 * `clearance` row-major w x h [m]. Says why the planner found no path for
 * the robot disc: a gap narrower than the robot (0 < c < needed) or a map
 * that does not connect the two (0). */
double widestWayClearance(const std::vector<float>& clearance, int w, int h,
                          int32_t start, int32_t goal);
}  // namespace risknav::planning
