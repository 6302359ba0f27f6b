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
 * mapping::CDistanceField (the outside of the map counted as an obstacle when
 * rule.outside_is_obstacle, the default). An obstacle cell is a square of side
 * res, and the robot is a disc of radius r: the robot touches an obstacle iff
 * its centre lies in the grown set O_r = {q : dist(q, O) <= r}, the exact
 * Minkowski sum of the obstacle squares (and the outside) with the disc, NOT
 * the obstacle squares grown by r rounded to whole cells. Each grown square is
 * a rounded square: the union of two rectangles (the square widened by r, and
 * heightened by r) and four discs of radius r at its corners; the outside
 * grown by r is the outside of the map shrunk by r on every side. */
class CObstacleField {
  public:
    /** robotRadius [m] in [0, 5] (0: a point robot). Throws
     * common::CConfigKeyError when the rule (TObstacleRule::validate()) or the
     * radius is out of range. */
    CObstacleField(const mrpt::maps::COccupancyGridMap2D& grid,
                   const mapping::TObstacleRule& rule, double robotRadius);

    /** D_max(x) = min over q in O_r of sqrt((q - x)^T Sigma^-1 (q - x)), the
     * Mahalanobis distance at which the ellipse of eq. (28) first touches the
     * grown obstacles (Irie et al. section 5.1, eqs. 28-29). Exact: rectangle
     * pieces in closed form; a disc piece by its Lagrange dual
     * max_{lambda >= 0} sum_i lambda l_i d_i^2 / (l_i + lambda) - lambda r^2
     * (l_i: eigenvalues of Sigma^-1, d: disc centre - x in its eigenbasis),
     * solved by safeguarded Newton on the secular equation; any lambda gives a
     * lower bound (weak duality), so what rounding remains lies on the safe
     * side (a smaller D_max). Only the discs at convex corners of the obstacle
     * union are evaluated (elsewhere the neighbours' rectangles cover them).
     * Sigma: 2x2 position covariance [m^2], any finite symmetric PSD matrix; a
     * (near-)singular Sigma is regularized with (1e-6 m)^2 I. Robot inside a
     * grown obstacle (or within r of the outside when it is an obstacle): 0.
     * +inf when there is no obstacle at all. NaN when Sigma is not finite.
     *
     * For fixed y, D^2 = a dx^2 + 2 b dx dy + c dy^2 is a convex parabola in x
     * with its minimum at x*(y) = x - b/a (y - y_robot). The rounded squares of
     * one row of cells have the same cross-section half-width w(y) <= r at
     * height y, so in the row's band widened by r only the squares within r
     * of the segment x*(band) and the nearest obstacle on either side of it
     * can hold the minimum (per-row "nearest obstacle left/right" indexes over
     * the raw obstacles), and every point of a band at vertical gap dy has D^2
     * >= dy^2 / Sigma_yy: bands are visited outwards only while that bound
     * beats the best so far. Cost ~ the rows the maximum ellipse spans, not the
     * number of obstacle cells. */
    TDmax dMax(double x, double y, const Eigen::Matrix2d& cov) const;
    /** The same by brute force over every raw obstacle square's full rounded
     * square (no convex-corner pruning) and, with outside_is_obstacle, the
     * outside shrunk by r (the reference of the tests). */
    TDmax dMaxBruteForce(double x, double y, const Eigen::Matrix2d& cov) const;

    /** Is the point (x, y) in the grown obstacles O_r (within r of an obstacle
     * square, or of the outside when it is an obstacle)? Exact: the distance
     * field decides when it can, the squares within r + res otherwise. */
    bool isObstacleAt(double x, double y) const;
    /** The cell-centre test of the grown obstacles: isObstacleAt(centre of the
     * cell); off the map: rule().outside_is_obstacle. */
    bool isObstacle(int cx, int cy) const {
        return m_df.inside(cx, cy) ? m_obst[size_t(cy) * m_df.sizeX() + cx] != 0
                                   : m_df.rule().outside_is_obstacle;
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
    /** Cells of the map whose centre lies in the grown obstacles. */
    size_t obstacleCount() const { return m_nGrown; }
    const mapping::TObstacleRule& rule() const { return m_df.rule(); }
    double robotRadius() const { return m_radius; }
    /** The raw (not grown) obstacles and their clearances. */
    const mapping::CDistanceField& distanceField() const { return m_df; }

  private:
    bool rawObstacle(int cx, int cy) const { return m_df.isObstacle(cx, cy); }

    mapping::CDistanceField m_df;
    double m_radius = 0;
    std::vector<uint8_t> m_obst;  // grown, cell-centre test, row-major
    size_t m_nGrown = 0;
    std::vector<int32_t> m_left, m_right;  // per cell: nearest RAW obstacle column
                                           // <= / >= cx in the row; -1 / sizeX if none
    std::vector<uint8_t> m_convex;         // per raw obstacle cell: bit k set when its
                                           // corner k (0: xl yl, 1: xh yl, 2: xl yh,
                                           // 3: xh yh) is convex (disc needed)
    std::vector<uint32_t> m_raw;           // raw obstacle cells, index cy * w + cx
};

}  // namespace risknav::risk
