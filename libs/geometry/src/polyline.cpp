#include <risknav/geometry/polyline.h>

using mrpt::math::TPoint2D;

namespace risknav::geometry {
double polylineLength(const std::vector<TPoint2D>& p) {
    double L = 0;
    for (size_t i = 1; i < p.size(); i++)
        L += std::hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y);
    return L;
}

std::vector<TPoint2D> simplifyDouglasPeucker(const std::vector<TPoint2D>& pts,
                                             double tolerance,
                                             const TShortcutTest& shortcutOk) {
    if (pts.size() <= 2)
        return pts;
    std::vector<bool> keep(pts.size(), false);
    keep.front() = keep.back() = true;
    std::vector<std::pair<size_t, size_t>> stack = {{0, pts.size() - 1}};
    while (!stack.empty()) {
        const auto [i, j] = stack.back();
        stack.pop_back();
        if (j <= i + 1)
            continue;
        const double ax = pts[i].x, ay = pts[i].y, vx = pts[j].x - ax, vy = pts[j].y - ay;
        const double L = std::hypot(vx, vy);
        size_t far = i + 1;
        double farD = -1;
        for (size_t k = i + 1; k < j; k++) {
            const double d =
                L > 0 ? std::abs((pts[k].x - ax) * vy - (pts[k].y - ay) * vx) / L
                      : std::hypot(pts[k].x - ax, pts[k].y - ay);
            if (d > farD) {
                farD = d;
                far = k;
            }
        }
        if (farD > tolerance || (shortcutOk && !shortcutOk(pts[i], pts[j]))) {
            keep[far] = true;
            stack.push_back({i, far});
            stack.push_back({far, j});
        }
    }
    std::vector<TPoint2D> out;
    for (size_t k = 0; k < pts.size(); k++)
        if (keep[k])
            out.push_back(pts[k]);
    return out;
}

}  // namespace risknav::geometry
