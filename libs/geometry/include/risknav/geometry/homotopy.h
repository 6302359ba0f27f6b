#pragma once
#include <mrpt/math/TPoint2D.h>

#include <cmath>
#include <functional>
#include <vector>

/** Homotopy of routes: do two routes with the same ends go the same way
 * around the obstacles? Used to keep only routes that are really different
 * (risk evaluator, M2; viewpoint planner, M4). */
namespace risknav::geometry {
/** The obstacles as a raster on the plane, without tying geometry to any map
 * class: cell (cx, cy), 0 <= cx < sizeX, 0 <= cy < sizeY, covers
 * [xMin + cx res, xMin + (cx + 1) res) x [yMin + cy res, yMin + (cy + 1) res)
 * and is an obstacle when isObstacle(cx, cy) (must be set). */
struct TObstacleRaster {
    int sizeX = 0, sizeY = 0;
    double xMin = 0, yMin = 0;
    double resolution = 1;  ///< [m] cell side, > 0
    std::function<bool(int cx, int cy)> isObstacle;

    int xToCol(double x) const { return int(std::floor((x - xMin) / resolution)); }
    int yToRow(double y) const { return int(std::floor((y - yMin) / resolution)); }
};

/** Are two routes with the same ends homotopic (the same way around the
 * obstacles)? True when the closed loop a + reverse(b), drawn on the raster
 * (cells of its vertices, filled with OpenCV's fillPoly, the boundary
 * included), covers no obstacle cell. A raster test, not an exact one: thin
 * obstacles between two routes closer than a cell are not seen, and the
 * loop's boundary cells count as enclosed, so routes must keep off obstacle
 * cells (as collision-free routes on that raster do). Cells outside the
 * raster are free. */
bool sameHomotopy(const std::vector<mrpt::math::TPoint2D>& a,
                  const std::vector<mrpt::math::TPoint2D>& b,
                  const TObstacleRaster& obstacles);

}  // namespace risknav::geometry
