#pragma once
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <Eigen/Dense>

#include <cstdint>
#include <limits>
#include <vector>

namespace risknav::risk {
/** Result of a D_max query: the Mahalanobis distance at which the position
 * error ellipse first touches an obstacle, and the obstacle cell it touches. */
struct TDmax {
    double d = std::numeric_limits<double>::infinity();  ///< inf: no obstacle in the map
    double touchX = 0, touchY = 0;                       ///< the touched point [m]
};

/** The obstacles of an occupancy grid, grown by the robot radius, indexed for
 * exact D_max queries (Irie et al. (001) section 5.1; PAPER_NOTES M2).
 *
 * A cell is an obstacle when its occupancy 1 - P(free) is at least
 * occupied_threshold; cells between free_threshold and occupied_threshold are
 * unknown and count as obstacles or free space (unknown_is_obstacle). The robot
 * is a disc: every cell whose centre lies within robot_radius of an obstacle
 * cell's centre is an obstacle of the grown map, so "the ellipse touches a grown
 * obstacle" = "the robot disc touches an obstacle". Cells outside the map are
 * not obstacles. */
class CObstacleField {
  public:
    struct TOptions {
        double occupied_threshold = 0.65;  ///< occupancy >= this: obstacle
        double free_threshold = 0.35;      ///< occupancy <= this: free; between: unknown
        bool unknown_is_obstacle = true;
        double robot_radius = 0.25;  ///< [m]
    };

    CObstacleField(const mrpt::maps::COccupancyGridMap2D& grid, const TOptions& opts);

    /** D_max(x) = min over the points q of the grown obstacle cells (squares of
     * side res, not their centres) of sqrt((q - x)^T Sigma^-1 (q - x)): the D
     * at which the ellipse of eq. (28) first touches an obstacle. Exact for
     * the grid: a wall is a continuous edge, so D_max does not jump as the
     * robot passes cell centres (it would when sigma << resolution). Sigma: 2x2
     * position covariance [m^2]; a (near-)singular Sigma is regularized with
     * (1e-6 m)^2 I. Robot inside a grown obstacle: 0.
     *
     * For fixed y, D^2 = a dx^2 + 2 b dx dy + c dy^2 is a convex parabola in x
     * with its minimum at x*(y) = x - b/a (y - y_robot); so in a row band only the
     * obstacle cells under the segment x*(band) and the nearest obstacle on
     * either side of it can hold the minimum (found through per-row "nearest
     * obstacle left/right" indexes), and every point of a band at vertical gap
     * dy has D^2 >= dy^2 / Sigma_yy, so bands are visited outwards only while
     * that bound beats the best so far. Cost ~ the rows the maximum ellipse
     * spans, not the number of obstacle cells. */
    TDmax dMax(double x, double y, const Eigen::Matrix2d& cov) const;
    /** The same by brute force over every grown obstacle square (the reference). */
    TDmax dMaxBruteForce(double x, double y, const Eigen::Matrix2d& cov) const;

    bool isObstacle(int cx, int cy) const {
        return cx >= 0 && cy >= 0 && cx < m_w && cy < m_h &&
               m_obst[size_t(cy) * m_w + cx];
    }
    bool isObstacleAt(double x, double y) const {
        return isObstacle(xToCol(x), yToRow(y));
    }
    /** Is the straight segment free of grown obstacles (sampled at res/2,
     * geometry::segmentFree)? */
    bool segmentFree(double x0, double y0, double x1, double y1) const;
    /** Distance [m] from (x, y) to the nearest RAW (not grown) obstacle cell centre. */
    double clearance(double x, double y) const;

    int sizeX() const { return m_w; }
    int sizeY() const { return m_h; }
    double resolution() const { return m_res; }
    double xMin() const { return m_xmin; }
    double yMin() const { return m_ymin; }
    int xToCol(double x) const { return int(std::floor((x - m_xmin) / m_res)); }
    int yToRow(double y) const { return int(std::floor((y - m_ymin) / m_res)); }
    double colToX(int cx) const { return m_xmin + (cx + 0.5) * m_res; }
    double rowToY(int cy) const { return m_ymin + (cy + 0.5) * m_res; }
    size_t obstacleCount() const { return m_cells.size(); }
    const TOptions& options() const { return m_opts; }
    /** Raw obstacle mask (before growing), row-major, 1 = obstacle. */
    const std::vector<uint8_t>& rawObstacles() const { return m_raw; }

  private:
    TOptions m_opts;
    int m_w = 0, m_h = 0;
    double m_xmin = 0, m_ymin = 0, m_res = 0;
    std::vector<uint8_t> m_raw, m_obst;
    std::vector<float> m_clearance;
    std::vector<int32_t> m_left, m_right;  // per cell: nearest obstacle column <= / >= cx
                                           // in the row; -1 / m_w if none
    std::vector<uint32_t> m_cells;         // grown obstacle cells, index cy * w + cx
};

}  // namespace risknav::risk
