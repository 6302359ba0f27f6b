#pragma once
#include <risknav/mapping/free_space.h>

#include <mrpt/math/TPoint2D.h>

#include <cstdint>
#include <vector>

namespace risknav::mapping {
/** A coarse memory, fixed in the ego frame, of what the robot-centred
 * free-space maps have shown: free, obstacle or unknown per cell.
 *
 * Beyond the paper: Miura et al. (000) plan in a 10 m robot-centred map and
 * pick a temporary destination on its free/undecided boundary nearest the
 * goal in a straight line; their destinations lay inside that map. A goal
 * 15 m away behind a dead end needs more: what scrolled out of the local map
 * is forgotten, and a closed room whose far wall scrolled out looks open
 * again. The memory keeps it, coarsely, only to rank the ways on
 * (costToGoal); speeds, paths and the undecided rule stay on the local map.
 *
 * A memory cell is an obstacle if any of its fine cells in the local map is
 * one (also where the local map covers only part of it: a wall on the
 * window's edge); free if the local map covers at least half of it and at
 * least half of those cells are free; otherwise it keeps what it had (an
 * obstacle seen free again, e.g. a person gone, becomes free). */
class CFreeSpaceMemory {
  public:
    enum class TState : uint8_t { Unknown, Free, Obstacle };

    /** A square of side `size` [m] centred on (cx, cy), cells of
     * `resolution` [m]; throws std::invalid_argument for sizes <= 0 or more
     * than 4096 cells a side. */
    CFreeSpaceMemory(double size, double resolution, double cx, double cy);

    void update(const TFreeSpaceMap& local);

    /** Cost [m] of the way on from every cell to `goal` BEYOND the local map
     * `window` (8-connected Dijkstra from the goal, no corner cutting past
     * obstacles): a metre of remembered free cell costs 1, a metre of
     * unknown `unknownWeight`; obstacles grown by `robotRadius` (not
     * around the goal), and the cells the window (the local map) holds as
     * free (the local planner's part of the way), cannot be crossed, nor
     * the memory more than 5 m around the window and the goal (a bound on
     * the search; cost stays +inf there). So a frontier's way on starts in the unknown
     * next to it, and a local map edge's in what lies beyond it: a closed room that
     * scrolled out of the window has no way on. */
    void computeCostToGoal(const mrpt::math::TPoint2D& goal, double unknownWeight,
                           const TFreeSpaceMap& window, double robotRadius);
    /** After computeCostToGoal: the least cost + distance over the cells
     * within `reach` [m] of (x, y); +inf when none has a way on; outside the
     * memory: unknownWeight x the straight line. */
    double costToGoal(double x, double y, double reach) const;

    TState at(double x, double y) const;
    int size() const { return m_n; }
    double resolution() const { return m_res; }

  private:
    int m_n;
    double m_res, m_xMin, m_yMin;
    std::vector<TState> m_cells;
    std::vector<float> m_cost;
    mrpt::math::TPoint2D m_goal;
    double m_weight = 1;
    int x2idx(double x) const;
    int y2idx(double y) const;
};
}  // namespace risknav::mapping
