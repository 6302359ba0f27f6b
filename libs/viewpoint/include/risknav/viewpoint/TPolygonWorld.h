#pragma once
#include <risknav/geometry/segments.h>
#include <risknav/mapping/TObstacleRule.h>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPoint2D.h>

#include <string>
#include <vector>

namespace risknav::viewpoint {
/** A distinguishable circular landmark on a wall (Yamashita et al. 003
 * section 2.2): seen only from the front, i.e. from the half-plane its
 * facing direction points into. */
struct TLandmark {
    std::string id;
    double x = 0, y = 0;   ///< [m] centre, on the wall
    double facing = 0;     ///< [rad] direction the landmark faces (its normal)
    double radius = 0.05;  ///< [m] (003 section 6: r = 50 mm)
    size_t line = 0;       ///< line in the world file (0: built in code)
};

/** A solid obstacle: an outer ring and optional holes (free space inside it,
 * e.g. the inside of a closed room when a grid's walls are traced). */
struct TObstacle {
    std::vector<mrpt::math::TPoint2D> outer;
    std::vector<std::vector<mrpt::math::TPoint2D>> holes;
    size_t line = 0;  ///< line of its `obstacle` in the world file (0: built in code)
};

/** The known map of the viewpoint planner (M4): a rectangle with walls all
 * round, polygon obstacles inside, landmarks on the walls. Every ring is
 * stored oriented with the obstacle on its left (outer rings
 * counter-clockwise, holes clockwise), so that "convex corner" and "outward
 * normal" mean the same on every ring. */
struct TPolygonWorld {
    double xMin = 0, yMin = 0, xMax = 0, yMax = 0;  ///< [m] the outer walls
    std::vector<TObstacle> obstacles;
    std::vector<TLandmark> landmarks;

    /** Every boundary ring, obstacle on the left: outer rings, holes, and the
     * outer walls (the bounds, clockwise). */
    std::vector<std::vector<mrpt::math::TPoint2D>> rings() const;
    /** The edges of rings(). */
    std::vector<geometry::TSegment> edges() const;
    /** Inside an obstacle (outer ring minus holes) or outside the bounds. */
    bool insideObstacle(const mrpt::math::TPoint2D& p) const;
    /** A point inside each obstacle (for homotopy classes of routes). */
    std::vector<mrpt::math::TPoint2D> obstacleReferencePoints() const;
};

/** @name The polygon world text format (documented in config/risknav-viewpoint-plan.ini)
 * Lines, `#` starts a comment, units metres and degrees:
 *   bounds XMIN YMIN XMAX YMAX           (once: the outer walls)
 *   obstacle X1 Y1 X2 Y2 X3 Y3 ...       (a simple polygon, >= 3 vertices, any
 * orientation) hole X1 Y1 X2 Y2 X3 Y3 ...           (a hole in the obstacle just before)
 *   landmark ID X Y FACING_DEG [RADIUS]  (on a wall, facing free space; radius 0.05 m;
 *                                         ID: up to 64 of A-Z a-z 0-9 _ . : -)
 * Every problem throws CBadInputError "file:line: what" (file alone for the
 * checks of the whole world).
 * @{ */
TPolygonWorld parsePolygonWorld(const std::string& text, const std::string& where,
                                bool requireBounds = true);
TPolygonWorld loadPolygonWorld(const std::string& path, bool requireBounds = true);
/** The checks of the whole world (also of one built in code): bounds with
 * positive area; every ring simple, obstacles inside the bounds, holes
 * inside their obstacle; every landmark
 * inside the bounds with a unique id and its front (1 mm along its facing)
 * in free space (not inside an obstacle, not facing into its wall). */
void validateWorld(const TPolygonWorld& w, const std::string& where);
/** @} */

/** Obstacles traced from an occupancy grid: the obstacle cells of `rule`,
 * dilated by one cell (the traced contour runs through cell centres, so the
 * dilation keeps the polygon outside every obstacle cell), outer contours
 * and holes with OpenCV's findContours (RETR_CCOMP), simplified with
 * approxPolyDP to `tolerance` [m] (which can cut up to that much off a
 * convex corner). Blobs of fewer than 2 cells are ignored. */
std::vector<TObstacle> obstaclesFromGrid(const mrpt::maps::COccupancyGridMap2D& grid,
                                         const mapping::TObstacleRule& rule,
                                         double tolerance);

/** Landmarks given on a grid's walls sit up to a cell inside the traced
 * contour (which runs outside the obstacle cells): each landmark whose front
 * is inside an obstacle and that lies within `tolerance` [m] of an obstacle
 * edge is moved onto the nearest edge point (its facing kept). Returns how
 * many moved; the others are left for validateWorld() to refuse. */
size_t snapLandmarksToWalls(TPolygonWorld& w, double tolerance);

/** Limits of what a world file may ask for (memory and time stay bounded). */
struct TWorldLimits {
    static constexpr size_t kMaxVertices = 100000;     ///< all rings together
    static constexpr size_t kMaxRingVertices = 10000;  ///< one polygon
    static constexpr size_t kMaxLandmarks = 2000;
    static constexpr double kMaxCoordinate = 1e5;  ///< [m]
    static constexpr size_t kMaxIdLength = 64;     ///< landmark ids: [A-Za-z0-9_.:-]
};

}  // namespace risknav::viewpoint
