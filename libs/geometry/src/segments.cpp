#include <risknav/geometry/segments.h>

#include <algorithm>
#include <cmath>

using mrpt::math::TPoint2D;

namespace risknav::geometry {
double pointSegmentDistance(const TPoint2D& p, const TPoint2D& a, const TPoint2D& b) {
    const double vx = b.x - a.x, vy = b.y - a.y, wx = p.x - a.x, wy = p.y - a.y;
    const double L2 = vx * vx + vy * vy;
    double t = L2 > 0 ? (wx * vx + wy * vy) / L2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(wx - t * vx, wy - t * vy);
}

namespace {
bool onSegment(const TPoint2D& a, const TPoint2D& b, const TPoint2D& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
           std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}
int sign(double v) {
    return (v > 0) - (v < 0);
}
}  // namespace

bool segmentsIntersect(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c,
                       const TPoint2D& d) {
    const int o1 = sign(orient(a, b, c)), o2 = sign(orient(a, b, d));
    const int o3 = sign(orient(c, d, a)), o4 = sign(orient(c, d, b));
    if (o1 != o2 && o3 != o4)
        return true;
    return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
           (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}

double segmentSegmentDistance(const TPoint2D& a, const TPoint2D& b, const TPoint2D& c,
                              const TPoint2D& d) {
    if (segmentsIntersect(a, b, c, d))
        return 0;
    // Disjoint segments: the minimum is attained at an end point of one of them.
    return std::min(
        std::min(pointSegmentDistance(a, c, d), pointSegmentDistance(b, c, d)),
        std::min(pointSegmentDistance(c, a, b), pointSegmentDistance(d, a, b)));
}

double signedArea(const std::vector<TPoint2D>& r) {
    double A = 0;
    for (size_t i = 0, n = r.size(); i < n; i++) {
        const auto& p = r[i];
        const auto& q = r[(i + 1) % n];
        A += p.x * q.y - q.x * p.y;
    }
    return A / 2;
}

bool pointInRing(const std::vector<TPoint2D>& r, const TPoint2D& p) {
    bool in = false;
    for (size_t i = 0, n = r.size(), j = n - 1; i < n; j = i++) {
        const auto& a = r[i];
        const auto& b = r[j];
        if ((a.y > p.y) != (b.y > p.y) &&
            p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
            in = !in;
    }
    return in;
}

int windingNumber(const std::vector<TPoint2D>& loop, const TPoint2D& p) {
    int w = 0;
    for (size_t i = 0, n = loop.size(); i < n; i++) {
        const auto& a = loop[i];
        const auto& b = loop[(i + 1) % n];
        if (a.y <= p.y) {
            if (b.y > p.y && orient(a, b, p) > 0)
                w++;
        } else if (b.y <= p.y && orient(a, b, p) < 0)
            w--;
    }
    return w;
}

bool ringIsSimple(const std::vector<TPoint2D>& r) {
    const size_t n = r.size();
    if (n < 3)
        return false;
    for (size_t i = 0; i < n; i++)
        if (r[i].x == r[(i + 1) % n].x && r[i].y == r[(i + 1) % n].y)
            return false;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
            const auto &a = r[i], &b = r[(i + 1) % n], &c = r[j], &d = r[(j + 1) % n];
            if (adjacent) {
                // Adjacent edges share one vertex; they may not fold back onto
                // each other (collinear and overlapping).
                const TPoint2D& shared = j == i + 1 ? b : a;
                const TPoint2D& far1 = j == i + 1 ? a : b;
                const TPoint2D& far2 = j == i + 1 ? d : c;
                if (orient(far1, shared, far2) == 0 &&
                    (far2.x - shared.x) * (far1.x - shared.x) +
                            (far2.y - shared.y) * (far1.y - shared.y) >
                        0)
                    return false;
                continue;
            }
            if (segmentsIntersect(a, b, c, d))
                return false;
        }
    return true;
}

}  // namespace risknav::geometry
