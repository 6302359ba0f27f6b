#pragma once
#include <risknav/mapping/TObstacleRule.h>

#include <mrpt/maps/COccupancyGridMap2D.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace risknav::mapping {
/** For every cell of a CDistanceField, its nearest obstacle cell: a discrete
 * Voronoi partition of the cells by their obstacle cells (the ring outside the
 * map included when the rule makes it an obstacle). What a Generalized Voronoi
 * Graph is read from (Irie et al. (001) section 6.1, eq. 31: points whose two
 * closest obstacles lie apart). */
struct TNearestObstacles {
    int sizeX = 0, sizeY = 0;
    /** Row-major, sizeX * sizeY: the nearest obstacle cell's indices (-1 or
     * sizeX / sizeY for a ring cell); an obstacle cell names itself. */
    std::vector<int32_t> obstX, obstY;
    /** Row-major: the distance to it [cells], OpenCV's 5x5 chamfer distance
     * (within 2 % of Euclidean): OpenCV labels nearest pixels only with the
     * 3x3 and 5x5 masks, not with the exact transform. */
    std::vector<float> distCells;
    bool any = false;  ///< false: no obstacle at all (every entry meaningless)

    size_t index(int cx, int cy) const { return size_t(cy) * sizeX + cx; }
};

/** The obstacles of an occupancy grid under one TObstacleRule, and the
 * clearance of every cell: the Euclidean distance [m] from its centre to the
 * nearest obstacle cell centre (OpenCV's exact distance transform), with the
 * ring of cells just outside the map counted as obstacles when the rule says
 * so. Shared by the simulator (collisions, route checks), the risk evaluator
 * (D_max, GVG) and the afraid learner (scan-to-map agreement).
 *
 * Cell indexing is MRPT's: cell (cx, cy) covers [xMin + cx res, xMin + (cx+1)
 * res); x2idx() floors, so it equals COccupancyGridMap2D::x2idx() on the map
 * and is negative (not 0) left of it. */
class CDistanceField {
  public:
    CDistanceField() = default;
    CDistanceField(const mrpt::maps::COccupancyGridMap2D& grid,
                   const TObstacleRule& rule);

    int sizeX() const { return m_w; }
    int sizeY() const { return m_h; }
    double resolution() const { return m_res; }
    double xMin() const { return m_xmin; }
    double yMin() const { return m_ymin; }
    double xMax() const { return m_xmin + m_w * m_res; }
    double yMax() const { return m_ymin + m_h * m_res; }
    int x2idx(double x) const { return int(std::floor((x - m_xmin) / m_res)); }
    int y2idx(double y) const { return int(std::floor((y - m_ymin) / m_res)); }
    double idx2x(int cx) const { return m_xmin + (cx + 0.5) * m_res; }
    double idx2y(int cy) const { return m_ymin + (cy + 0.5) * m_res; }
    bool inside(int cx, int cy) const {
        return cx >= 0 && cy >= 0 && cx < m_w && cy < m_h;
    }
    const TObstacleRule& rule() const { return m_rule; }

    /** Obstacle by the rule; outside the map: rule().outside_is_obstacle. */
    bool isObstacle(int cx, int cy) const {
        return inside(cx, cy) ? m_obst[size_t(cy) * m_w + cx] != 0
                              : m_rule.outside_is_obstacle;
    }
    bool isObstacleAt(double x, double y) const { return isObstacle(x2idx(x), y2idx(y)); }

    /** Clearance [m] of a cell. Off the map: 0 when outside is an obstacle,
     * else the clearance of the nearest map cell. +inf when the map (and its
     * outside) holds no obstacle. */
    double clearance(int cx, int cy) const;
    double clearanceAt(double x, double y) const { return clearance(x2idx(x), y2idx(y)); }
    /** Exact distance [m] from the point (x, y) to the nearest obstacle
     * cell's square (clearanceAt() measures cell centre to cell centre and
     * can be up to a cell too large): searched over the cells within
     * `reach` [m]; beyond it clearanceAt(). 0 inside an obstacle cell. For
     * collision checks, where 5 cm of overlap must not go uncounted. */
    double pointClearance(double x, double y, double reach) const;

    /** Depth [m] of an obstacle cell: the distance from its centre to the
     * nearest free cell centre (0 for a free cell; off the map: 0). A scan
     * point deep inside a wall is as wrong as one far from every wall. */
    double depth(int cx, int cy) const {
        return inside(cx, cy) && !m_depth.empty() ? m_depth[size_t(cy) * m_w + cx] : 0.0;
    }
    double depthAt(double x, double y) const { return depth(x2idx(x), y2idx(y)); }

    /** Row-major masks / values, sizeX() * sizeY(). */
    const std::vector<uint8_t>& obstacles() const { return m_obst; }
    const std::vector<float>& clearances() const { return m_dist; }
    size_t obstacleCount() const { return m_nObst; }
    size_t freeCount() const { return m_obst.size() - m_nObst; }

    /** Every cell's nearest obstacle cell (computed on each call: a labelled
     * distance transform of the same obstacles, ring included by the rule). */
    TNearestObstacles nearestObstacles() const;

  private:
    TObstacleRule m_rule;
    int m_w = 0, m_h = 0;
    double m_xmin = 0, m_ymin = 0, m_res = 1;
    std::vector<uint8_t> m_obst;
    std::vector<float> m_dist, m_depth;
    size_t m_nObst = 0;
};

}  // namespace risknav::mapping
