#pragma once
#include <mrpt/math/TPoint2D.h>

#include <vector>

/** Exact planar primitives on segments and rings (closed polygons given by
 * their vertices, the closing edge implied): distances, intersection,
 * inside tests, winding numbers. Pure functions, shared by every planner that
 * works on polygon maps (viewpoint planner, M4). */
namespace risknav::geometry {
struct TSegment {
    mrpt::math::TPoint2D a, b;
};

/** z of (b - a) x (c - a): > 0 when c is left of a->b. */
inline double orient(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
                     const mrpt::math::TPoint2D& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/** Euclidean distance from p to the closed segment [a, b] (a == b allowed). */
double pointSegmentDistance(const mrpt::math::TPoint2D& p, const mrpt::math::TPoint2D& a,
                            const mrpt::math::TPoint2D& b);

/** Do the closed segments [a, b] and [c, d] share a point (touching counts)? */
bool segmentsIntersect(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
                       const mrpt::math::TPoint2D& c, const mrpt::math::TPoint2D& d);

/** Distance between the closed segments [a, b] and [c, d]; 0 when they meet. */
double segmentSegmentDistance(const mrpt::math::TPoint2D& a,
                              const mrpt::math::TPoint2D& b,
                              const mrpt::math::TPoint2D& c,
                              const mrpt::math::TPoint2D& d);

/** Signed area of a ring: > 0 counter-clockwise (shoelace formula). */
double signedArea(const std::vector<mrpt::math::TPoint2D>& ring);

/** Is p strictly inside the ring (even-odd crossing rule; points on the
 * boundary may go either way)? */
bool pointInRing(const std::vector<mrpt::math::TPoint2D>& ring,
                 const mrpt::math::TPoint2D& p);

/** Winding number of the closed loop (vertices, the closing edge implied)
 * around p: the number of counter-clockwise turns; p must not lie on it. Two
 * paths with the same ends go the same way around an obstacle exactly when
 * the loop path1 + reverse(path2) winds 0 times around a point inside it. */
int windingNumber(const std::vector<mrpt::math::TPoint2D>& loop,
                  const mrpt::math::TPoint2D& p);

/** Is the ring simple: >= 3 vertices, no two non-adjacent edges meeting, no
 * zero-length edge? O(n^2), for input checks. */
bool ringIsSimple(const std::vector<mrpt::math::TPoint2D>& ring);

}  // namespace risknav::geometry
