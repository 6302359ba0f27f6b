#pragma once
#include <risknav/mapping/CDistanceField.h>

#include <mrpt/maps/COccupancyGridMap2D.h>

#include <Eigen/Dense>

#include <cstdint>
#include <limits>
#include <vector>

namespace risknav::risk {
/** Result of a D_max query: the Mahalanobis distance at which the position
 * error ellipse first touches an obstacle, and the obstacle cell it touches. */
struct TDmax {
    double d = std::numeric_limits<double>::infinity();  ///< inf: no obstacle at all
    double touchX = 0, touchY = 0;                       ///< the touched point [m]
};

/** The obstacles of an occupancy grid, grown by the robot radius, indexed for
 * exact D_max queries (Irie et al. (001) section 5.1; PAPER_NOTES M2).
 *
 * Which cells are obstacles is the shared mapping::TObstacleRule, measured by
 * mapping::CDistanceField (exact clearance of every cell, the ring of cells
 * just outside the map counted as obstacles when rule.outside_is_obstacle, the
 * default). The robot is a disc: every cell whose centre lies within the robot
 * radius of an obstacle cell's centre (ring cells included) is an obstacle of
 * the grown map, so "the ellipse touches a grown obstacle" = "the robot disc
 * touches an obstacle". With outside_is_obstacle everything off the map is an
 * obstacle too: a map without a border wall still bounds D_max. */
class CObstacleField {
  public:
    /** robotRadius [m] in [0, 5] (0: a point robot). Throws
     * common::CConfigKeyError when the rule (TObstacleRule::validate()) or the
     * radius is out of range. */
    CObstacleField(const mrpt::maps::COccupancyGridMap2D& grid,
                   const mapping::TObstacleRule& rule, double robotRadius);

    /** D_max(x) = min over the points q of the grown obstacle cells (squares of
     * side res, not their centres) and, with outside_is_obstacle, of the
     * outside of the map, of sqrt((q - x)^T Sigma^-1 (q - x)): the D at which
     * the ellipse of eq. (28) first touches an obstacle. Exact for the grid: a
     * wall is a continuous edge, so D_max does not jump as the robot passes
     * cell centres (it would when sigma << resolution). Sigma: 2x2 position
     * covariance [m^2]; a (near-)singular Sigma is regularized with
     * (1e-6 m)^2 I. Robot inside a grown obstacle (or off the map when the
     * outside is an obstacle): 0. +inf when there is no obstacle at all.
     *
     * The outside is the union of the four half-planes beyond the map's edges;
     * for the half-plane x <= x_min the minimum is (x - x_min) / sqrt(Sigma_xx)
     * (and alike for the others), the Mahalanobis distance to a line. It seeds
     * the search below.
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
    /** The same by brute force over every grown obstacle square and, with
     * outside_is_obstacle, every square of the ring just outside the map (for a
     * robot on the map the ring holds the outside's nearest point, as the
     * segment to any point beyond crosses it); a robot off the map is inside
     * the outside obstacle (the reference). */
    TDmax dMaxBruteForce(double x, double y, const Eigen::Matrix2d& cov) const;

    /** A grown obstacle; off the map: rule().outside_is_obstacle. */
    bool isObstacle(int cx, int cy) const {
        return m_df.inside(cx, cy) ? m_obst[size_t(cy) * m_df.sizeX() + cx] != 0
                                   : m_df.rule().outside_is_obstacle;
    }
    bool isObstacleAt(double x, double y) const {
        return isObstacle(xToCol(x), yToRow(y));
    }
    /** Is the straight segment free of grown obstacles (sampled at res/2,
     * geometry::segmentFree)? */
    bool segmentFree(double x0, double y0, double x1, double y1) const;
    /** Distance [m] from (x, y) to the nearest RAW (not grown) obstacle cell
     * centre (mapping::CDistanceField::clearanceAt). */
    double clearance(double x, double y) const { return m_df.clearanceAt(x, y); }

    int sizeX() const { return m_df.sizeX(); }
    int sizeY() const { return m_df.sizeY(); }
    double resolution() const { return m_df.resolution(); }
    double xMin() const { return m_df.xMin(); }
    double yMin() const { return m_df.yMin(); }
    int xToCol(double x) const { return m_df.x2idx(x); }
    int yToRow(double y) const { return m_df.y2idx(y); }
    double colToX(int cx) const { return m_df.idx2x(cx); }
    double rowToY(int cy) const { return m_df.idx2y(cy); }
    /** Grown obstacle cells on the map (the ring not counted). */
    size_t obstacleCount() const { return m_cells.size(); }
    const mapping::TObstacleRule& rule() const { return m_df.rule(); }
    double robotRadius() const { return m_radius; }
    /** The raw (not grown) obstacles and their clearances. */
    const mapping::CDistanceField& distanceField() const { return m_df; }

  private:
    mapping::CDistanceField m_df;
    double m_radius = 0;
    std::vector<uint8_t> m_obst;           // grown, row-major
    std::vector<int32_t> m_left, m_right;  // per cell: nearest obstacle column <= / >= cx
                                           // in the row; -1 / sizeX if none
    std::vector<uint32_t> m_cells;         // grown obstacle cells, index cy * w + cx
};

}  // namespace risknav::risk
