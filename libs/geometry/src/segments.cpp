#include <risknav/geometry/segments.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

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
    auto pt = [&](size_t i) -> const TPoint2D& { return r[i % n]; };
    // Zero-length edges, and adjacent edges folding back onto each other
    // (collinear and overlapping): one pass.
    for (size_t i = 0; i < n; i++) {
        const TPoint2D &a = pt(i), &b = pt(i + 1), &c = pt(i + 2);
        if (a.x == b.x && a.y == b.y)
            return false;
        if (orient(a, b, c) == 0 &&
            (c.x - b.x) * (a.x - b.x) + (c.y - b.y) * (a.y - b.y) > 0)
            return false;
    }
    // Non-adjacent edges may not meet. Edges are bucketed in a grid of about
    // n cells over the ring's box, and only edges sharing a cell are tested:
    // O(n) for ordinary polygons (the input limits keep the worst case, every
    // edge through one cell, bounded).
    double x0 = r[0].x, x1 = x0, y0 = r[0].y, y1 = y0;
    for (const auto& p : r) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    const int G = std::max(1, int(std::ceil(std::sqrt(double(n)))));
    const double cw = std::max((x1 - x0) / G, 1e-300),
                 ch = std::max((y1 - y0) / G, 1e-300);
    auto cx = [&](double x) { return std::clamp(int((x - x0) / cw), 0, G - 1); };
    auto cy = [&](double y) { return std::clamp(int((y - y0) / ch), 0, G - 1); };
    std::vector<std::vector<uint32_t>> cells(size_t(G) * size_t(G));
    for (size_t i = 0; i < n; i++) {
        const TPoint2D &a = pt(i), &b = pt(i + 1);
        for (int y = cy(std::min(a.y, b.y)); y <= cy(std::max(a.y, b.y)); y++)
            for (int x = cx(std::min(a.x, b.x)); x <= cx(std::max(a.x, b.x)); x++)
                cells[size_t(y) * size_t(G) + size_t(x)].push_back(uint32_t(i));
    }
    for (const auto& c : cells)
        for (size_t u = 0; u < c.size(); u++)
            for (size_t v = u + 1; v < c.size(); v++) {
                const size_t i = std::min(c[u], c[v]), j = std::max(c[u], c[v]);
                if (j == i + 1 || (i == 0 && j == n - 1))
                    continue;  // adjacent: they share a vertex
                if (segmentsIntersect(pt(i), pt(i + 1), pt(j), pt(j + 1)))
                    return false;
            }
    return true;
}

}  // namespace risknav::geometry
