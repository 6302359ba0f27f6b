#pragma once
#include <mrpt/math/TPoint2D.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

/** Polylines on the plane (routes, paths): length, simplification and the
 * "is this straight segment free" test, with the obstacle test passed in so
 * that any map (grid, polygons) can use them. */
namespace risknav::geometry {
/** Sum of the Euclidean lengths of the segments [m]; 0 for fewer than 2 points. */
double polylineLength(const std::vector<mrpt::math::TPoint2D>& p);

/** May the simplification replace the points between a and b by the straight
 * segment a-b? (e.g. "the segment does not cross an obstacle"). */
using TShortcutTest =
    std::function<bool(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b)>;

/** Douglas-Peucker simplification (Douglas & Peucker 1973): keep the first
 * and last point; between two kept points i < j, if the farthest point k from
 * the line i-j is farther than `tolerance` [m] (from point i when i and j
 * coincide), or `shortcutOk(p_i, p_j)` is false, keep k and recurse on both
 * halves. So every dropped point lies within `tolerance` of the segment that
 * replaces it, and (with a shortcut test) no new segment cuts a corner across
 * an obstacle. An empty `shortcutOk` allows every shortcut. Iterative (no
 * recursion depth limit). */
std::vector<mrpt::math::TPoint2D> simplifyDouglasPeucker(
    const std::vector<mrpt::math::TPoint2D>& pts, double tolerance,
    const TShortcutTest& shortcutOk = {});

/** Is the straight segment (x0, y0) -> (x1, y1) free? Samples it at
 * n + 1 evenly spaced points, both ends included, n = max(1, ceil(length /
 * step)), and returns false at the first sample where isObstacle(x, y) is
 * true. With step = half a grid cell every cell the segment crosses by more
 * than a sliver is tested. A template (not std::function) because route
 * searches call it for thousands of segments. Throws std::invalid_argument
 * when step is not > 0. */
template <class IsObstacle>
bool segmentFree(double x0, double y0, double x1, double y1, double step,
                 IsObstacle&& isObstacle) {
    if (!(step > 0))
        throw std::invalid_argument("segmentFree: step must be > 0");
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int n = std::max(1, int(std::ceil(len / step)));
    for (int k = 0; k <= n; k++)
        if (isObstacle(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n))
            return false;
    return true;
}

/** Pure pursuit's look-ahead point on a polyline, as indices into `pts`:
 * `nearest`, the point nearest `from`, and `ahead`, the first point from
 * there on at least `lookahead` [m] from `from` (the last point if none is),
 * pulled back towards `nearest` until the straight line from `from` to it
 * keeps the clearance the polyline keeps between the two (or the clearance
 * at `from`, if less), to within `step` (a chord across a door post's corner would cut
 * past the margin). `clearanceAt(x, y)` [m] is the map's clearance; `step` [m] the
 * sampling of the chord (half a cell). Fewer than 2 points: both 0. Shared by the
 * adaptive controller's local paths and the global planner's routes. */
struct TLookahead {
    size_t nearest = 0, ahead = 0;
};
template <class ClearanceAt>
TLookahead lookaheadOnPolyline(const std::vector<mrpt::math::TPoint2D>& pts,
                               const mrpt::math::TPoint2D& from, double lookahead,
                               double step, ClearanceAt&& clearanceAt) {
    TLookahead r;
    if (pts.size() < 2)
        return r;
    double best = 1e18;
    for (size_t k = 0; k < pts.size(); k++) {
        const double d = std::hypot(pts[k].x - from.x, pts[k].y - from.y);
        if (d < best) {
            best = d;
            r.nearest = k;
        }
    }
    const size_t c = r.nearest;
    size_t t = c;
    while (t + 1 < pts.size() &&
           std::hypot(pts[t].x - from.x, pts[t].y - from.y) < lookahead)
        t++;
    auto chordKeepsClearance = [&](size_t to) {
        // a robot off the polyline (nearer a wall than it) starts the chord
        // with its own clearance: the chord need not keep more
        double pathClear = clearanceAt(from.x, from.y);
        for (size_t k = c; k <= to; k++)
            pathClear = std::min(pathClear, double(clearanceAt(pts[k].x, pts[k].y)));
        const double len = std::hypot(pts[to].x - from.x, pts[to].y - from.y);
        const int n = int(std::ceil(len / step));
        for (int s = 1; s <= n; s++) {
            const double f = double(s) / n;
            if (clearanceAt(from.x + f * (pts[to].x - from.x),
                            from.y + f * (pts[to].y - from.y)) < pathClear - step)
                return false;
        }
        return true;
    };
    while (t > c + 1 && !chordKeepsClearance(t))
        t--;
    r.ahead = t;
    return r;
}

}  // namespace risknav::geometry
