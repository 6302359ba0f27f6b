#include <risknav/common/config_read.h>
#include <risknav/geometry/polyline.h>
#include <risknav/risk/CObstacleField.h>

#include <algorithm>
#include <cmath>

namespace risknav::risk {
namespace {
// Inverse of a 2x2 covariance, regularized so that a zero or singular
// covariance (e.g. a perfectly known start) gives huge, finite distances.
void inverse2(const Eigen::Matrix2d& cov, double& a, double& b, double& c, double& syy) {
    Eigen::Matrix2d s = 0.5 * (cov + cov.transpose());
    const double eps = 1e-12;  // (1e-6 m)^2
    if (!(s.determinant() > eps * eps) || !(s(0, 0) > 0) || !(s(1, 1) > 0))
        s += eps * Eigen::Matrix2d::Identity();
    const double det = s(0, 0) * s(1, 1) - s(0, 1) * s(0, 1);
    a = s(1, 1) / det;
    b = -s(0, 1) / det;
    c = s(0, 0) / det;
    syy = s(1, 1);
}

const mapping::TObstacleRule& validated(const mapping::TObstacleRule& rule,
                                        double robotRadius) {
    rule.validate();
    common::checkKey("Robot", "radius", robotRadius, common::TRange::closed(0, 5, "m"));
    return rule;
}
}  // namespace

CObstacleField::CObstacleField(const mrpt::maps::COccupancyGridMap2D& g,
                               const mapping::TObstacleRule& rule, double robotRadius)
    : m_df(g, validated(rule, robotRadius)), m_radius(robotRadius) {
    const int w = m_df.sizeX(), h = m_df.sizeY();
    const size_t n = size_t(w) * h;
    // Grown by the robot radius (a hair of slack for float rounding): cells
    // within the radius of an obstacle cell, the outside ring included.
    const auto& clear = m_df.clearances();
    m_obst.assign(n, 0);
    for (size_t i = 0; i < n; i++)
        if (clear[i] <= robotRadius + 1e-6) {
            m_obst[i] = 1;
            m_cells.push_back(uint32_t(i));
        }
    m_left.resize(n);
    m_right.resize(n);
    for (int cy = 0; cy < h; cy++) {
        const size_t row = size_t(cy) * w;
        int last = -1;
        for (int cx = 0; cx < w; cx++) {
            if (m_obst[row + cx])
                last = cx;
            m_left[row + cx] = last;
        }
        last = w;
        for (int cx = w - 1; cx >= 0; cx--) {
            if (m_obst[row + cx])
                last = cx;
            m_right[row + cx] = last;
        }
    }
}

namespace {
// Keeps (x, y) as the touch point if q there beats best2.
void consider(double a, double b, double c, double px, double py, double x, double y,
              double& best2, TDmax& best) {
    const double dx = x - px, dy = y - py;
    const double q = a * dx * dx + 2 * b * dx * dy + c * dy * dy;
    if (q < best2) {
        best2 = q;
        best.touchX = x;
        best.touchY = y;
    }
}

void inside(double px, double py, double& best2, TDmax& best) {
    if (best2 > 0) {
        best2 = 0;
        best.touchX = px;
        best.touchY = py;
    }
}

// Minimum of q(dx, dy) = a dx^2 + 2 b dx dy + c dy^2 over the square
// [xl, xh] x [yl, yh] (world coordinates, robot at (px, py)): 0 if the robot is
// inside; else the minimum of the convex q lies on the boundary, and on each
// edge it is the 1-D minimum clamped to the edge.
void squareMin(double a, double b, double c, double px, double py, double xl, double xh,
               double yl, double yh, double& best2, TDmax& best) {
    if (px >= xl && px <= xh && py >= yl && py <= yh)
        return inside(px, py, best2, best);
    for (double y : {yl, yh})
        consider(a, b, c, px, py, std::clamp(px - b / a * (y - py), xl, xh), y, best2,
                 best);
    for (double x : {xl, xh})
        consider(a, b, c, px, py, x, std::clamp(py - b / c * (x - px), yl, yh), best2,
                 best);
}

// Minimum of q over the outside of the map [x0, x1] x [y0, y1]: the union of
// the half-planes x <= x0, x >= x1, y <= y0, y >= y1. On the line x = X the
// minimum is at y = py - b/c (X - px), q = (X - px)^2 (a - b^2/c) =
// (X - px)^2 / Sigma_xx: the Mahalanobis distance to a line (alike for y).
void outsideMin(double a, double b, double c, double px, double py, double x0, double x1,
                double y0, double y1, double& best2, TDmax& best) {
    if (px <= x0 || px >= x1 || py <= y0 || py >= y1)
        return inside(px, py, best2, best);
    for (double x : {x0, x1})
        consider(a, b, c, px, py, x, py - b / c * (x - px), best2, best);
    for (double y : {y0, y1})
        consider(a, b, c, px, py, px - b / a * (y - py), y, best2, best);
}
}  // namespace

TDmax CObstacleField::dMax(double x, double y, const Eigen::Matrix2d& cov) const {
    double a, b, c, syy;
    inverse2(cov, a, b, c, syy);
    TDmax best;
    double best2 = std::numeric_limits<double>::infinity();
    const int w = m_df.sizeX(), h = m_df.sizeY();
    const double res = m_df.resolution(), xmin = m_df.xMin(), ymin = m_df.yMin();
    if (m_df.rule().outside_is_obstacle)
        outsideMin(a, b, c, x, y, xmin, m_df.xMax(), ymin, m_df.yMax(), best2, best);
    // A row band: its obstacle cells that can hold the minimum are those under
    // the segment of parabola minima x*(y) = x - b/a (y - y), y in the band,
    // plus the nearest obstacle on either side of it (per-row indexes).
    auto visitRow = [&](int cy) {
        const double yl = ymin + cy * res, yh = yl + res;
        double lo = x - b / a * (yl - y), hi = x - b / a * (yh - y);
        if (lo > hi)
            std::swap(lo, hi);
        const int cL = std::clamp(xToCol(lo), 0, w - 1),
                  cR = std::clamp(xToCol(hi), 0, w - 1);
        const size_t row = size_t(cy) * w;
        auto cell = [&](int cx) {
            const double xl = xmin + cx * res;
            squareMin(a, b, c, x, y, xl, xl + res, yl, yh, best2, best);
        };
        if (m_left[row + cL] >= 0)
            cell(m_left[row + cL]);
        for (int cx = m_right[row + cL]; cx <= cR && cx < w;
             cx = cx + 1 < w ? m_right[row + cx + 1] : w)
            cell(cx);
        if (m_right[row + cR] < w)
            cell(m_right[row + cR]);
    };
    // Every point of a band is at least its vertical gap dy away, and
    // q >= dy^2 / Sigma_yy: visit bands outwards while they can still win.
    auto bandBound = [&](int cy) {
        const double yl = ymin + cy * res, yh = yl + res;
        const double dy = y < yl ? yl - y : (y > yh ? y - yh : 0.0);
        return dy * dy / syy;
    };
    const int cy0 = std::clamp(yToRow(y), 0, h - 1);
    for (int cy = cy0; cy < h && bandBound(cy) < best2; cy++)
        visitRow(cy);
    for (int cy = cy0 - 1; cy >= 0 && bandBound(cy) < best2; cy--)
        visitRow(cy);
    best.d = std::sqrt(std::max(0.0, best2));
    return best;
}

TDmax CObstacleField::dMaxBruteForce(double x, double y,
                                     const Eigen::Matrix2d& cov) const {
    double a, b, c, syy;
    inverse2(cov, a, b, c, syy);
    TDmax best;
    double best2 = std::numeric_limits<double>::infinity();
    const int w = m_df.sizeX(), h = m_df.sizeY();
    const double res = m_df.resolution(), xmin = m_df.xMin(), ymin = m_df.yMin();
    auto square = [&](int cx, int cy) {
        const double xl = xmin + cx * res, yl = ymin + cy * res;
        squareMin(a, b, c, x, y, xl, xl + res, yl, yl + res, best2, best);
    };
    for (uint32_t idx : m_cells)
        square(int(idx % uint32_t(w)), int(idx / uint32_t(w)));
    if (m_df.rule().outside_is_obstacle) {
        if (x < xmin || x > m_df.xMax() || y < ymin || y > m_df.yMax())
            inside(x, y, best2, best);  // off the map: in the outside obstacle
        for (int cx = -1; cx <= w; cx++) {
            square(cx, -1);
            square(cx, h);
        }
        for (int cy = 0; cy < h; cy++) {
            square(-1, cy);
            square(w, cy);
        }
    }
    best.d = std::sqrt(std::max(0.0, best2));
    return best;
}

bool CObstacleField::segmentFree(double x0, double y0, double x1, double y1) const {
    return geometry::segmentFree(
        x0, y0, x1, y1, 0.5 * resolution(),
        [this](double x, double y) { return isObstacleAt(x, y); });
}

}  // namespace risknav::risk
