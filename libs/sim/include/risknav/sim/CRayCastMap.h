#pragma once
#include <risknav/mapping/TObstacleRule.h>

#include <mrpt/maps/COccupancyGridMap2D.h>

namespace risknav::sim {
/** The static map as the simulated range sensors see it: every cell an
 * obstacle or free by the one obstacle rule, mapping::TObstacleRule::
 * isObstacle(), the function the collisions and clearances classify cells
 * with (mapping::CDistanceField). So the laser and the collision check agree
 * on every cell: an unknown cell echoes when unknown_is_obstacle (a robot
 * sees the wall it would hit) and is seen through otherwise (as it is driven
 * through); with outside_is_obstacle the ring of cells just off the map, a
 * wall for the collisions, is one for the rays too.
 *
 * The rays are cast by MRPT's COccupancyGridMap2D::laserScanSimulator on a
 * grid that holds only P(free) = 0 (obstacle) and 1 (free): MRPT's own
 * threshold, and its rule that a ray ending on a cell of P(free) ~ 0.5 gives
 * no echo, decide nothing. */
class CRayCastMap {
  public:
    CRayCastMap() = default;
    /** The map's cells classified by `rule`; with rule.outside_is_obstacle
     * the grid is one cell larger on every side (that ring an obstacle). */
    CRayCastMap(const mrpt::maps::COccupancyGridMap2D& map,
                const mapping::TObstacleRule& rule);

    /** The two-valued grid the rays are cast on. */
    const mrpt::maps::COccupancyGridMap2D& grid() const { return m_grid; }
    /** Whether the rays end in the cell holding (x, y); off grid(): false
     * (a ray leaves the grid without an echo). */
    bool isObstacleAt(double x, double y) const;

  private:
    mrpt::maps::COccupancyGridMap2D m_grid;
};

}  // namespace risknav::sim
