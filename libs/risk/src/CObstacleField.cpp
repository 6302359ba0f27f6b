#include <risknav/common/config_read.h>
#include <risknav/geometry/polyline.h>
#include <risknav/risk/CObstacleField.h>

#include <algorithm>
#include <cmath>

namespace risknav::risk {
namespace {
// The quadratic form q(dx, dy) = a dx^2 + 2 b dx dy + c dy^2 of Sigma^-1, and
// its eigen-decomposition: Sigma^-1 = l1 e1 e1^T + l2 e2 e2^T, e1 = (ex, ey),
// e2 = (-ey, ex).
struct TForm {
    double a = 0, b = 0, c = 0;
    double sxx = 0, syy = 0;  // Sigma (regularized)
    double l1 = 0, l2 = 0, ex = 1, ey = 0;
    double q(double dx, double dy) const {
        return a * dx * dx + 2 * b * dx * dy + c * dy * dy;
    }
};

// Sigma^-1 of a symmetric 2x2 covariance, regularized so that a zero, singular
// or (by rounding) slightly indefinite covariance gives huge, finite
// distances: its eigenvalues are raised to at least (1e-6 m)^2. Closed-form
// eigen-decomposition (no overflow for any finite Sigma). false if Sigma is
// not finite.
bool makeForm(const Eigen::Matrix2d& cov, TForm& f) {
    const double p = cov(0, 0), r = cov(1, 1), q = 0.5 * (cov(0, 1) + cov(1, 0));
    if (!std::isfinite(p) || !std::isfinite(r) || !std::isfinite(q))
        return false;
    const double mid = 0.5 * p + 0.5 * r, half = std::hypot(0.5 * p - 0.5 * r, q);
    const double phi = 0.5 * std::atan2(2 * (q * 0.5), 0.5 * p - 0.5 * r);
    const double eps = 1e-12;  // (1e-6 m)^2
    const double s1 = std::max(mid + half, eps), s2 = std::max(mid - half, eps);
    f.ex = std::cos(phi);
    f.ey = std::sin(phi);
    f.l1 = 1 / s1;
    f.l2 = 1 / s2;
    const double cc = f.ex * f.ex, ss = f.ey * f.ey, cs = f.ex * f.ey;
    f.a = f.l1 * cc + f.l2 * ss;
    f.b = (f.l1 - f.l2) * cs;
    f.c = f.l1 * ss + f.l2 * cc;
    f.sxx = s1 * cc + s2 * ss;
    f.syy = s1 * ss + s2 * cc;
    return true;
}

// A candidate minimum: q and the point where it is reached.
struct TCand {
    double q, x, y;
};

void keep(const TCand& k, double& best2, TDmax& best) {
    if (k.q < best2) {
        best2 = k.q;
        best.touchX = k.x;
        best.touchY = k.y;
    }
}

// Minimum of q over the rectangle [xl, xh] x [yl, yh] (world coordinates,
// robot at (px, py)): 0 if the robot is inside; else the minimum of the convex
// q lies on the boundary, and on each edge it is the 1-D minimum clamped to
// the edge.
TCand rectMin(const TForm& f, double px, double py, double xl, double xh, double yl,
              double yh) {
    if (px >= xl && px <= xh && py >= yl && py <= yh)
        return {0, px, py};
    TCand best{std::numeric_limits<double>::infinity(), px, py};
    auto consider = [&](double x, double y) {
        const double v = f.q(x - px, y - py);
        if (v < best.q)
            best = {v, x, y};
    };
    for (double y : {yl, yh})
        consider(std::clamp(px - f.b / f.a * (y - py), xl, xh), y);
    for (double x : {xl, xh})
        consider(x, std::clamp(py - f.b / f.c * (x - px), yl, yh));
    return best;
}

// Minimum of q over the disc |z - (cx, cy)| <= r (robot at p): 0 if p is in
// the disc; else, with d = centre - p in the eigenbasis of Sigma^-1 and
// y = z - p, the minimum of y^T A y subject to |y - d|^2 <= r^2 equals
// (strong duality, a convex problem) the maximum over lambda >= 0 of the
// Lagrange dual
//   h(lambda) = sum_i lambda l_i d_i^2 / (l_i + lambda) - lambda r^2,
// reached where |(A + lambda I)^-1 A d| = r (the secular equation, as in
// trust-region steps; Moré & Sorensen 1983). Solved by Newton on
// 1/r - 1/|(A + lambda I)^-1 A d|, safeguarded by bisection on the bracket
// [0, |A d| / r]. h(lambda) <= the minimum for EVERY lambda (weak duality): the
// value returned errs, if at all, on the safe side (a smaller D_max).
TCand discMin(const TForm& f, double px, double py, double cx, double cy, double r) {
    const double dx = cx - px, dy = cy - py;
    if (dx * dx + dy * dy <= r * r)
        return {0, px, py};
    const double d1 = f.ex * dx + f.ey * dy, d2 = -f.ey * dx + f.ex * dy;
    const double l1 = f.l1, l2 = f.l2;
    double lo = 0, hi = std::hypot(l1 * d1, l2 * d2) / r, lam = 0;
    for (int it = 0; it < 100; it++) {
        const double t1 = l1 * d1 / (l1 + lam), t2 = l2 * d2 / (l2 + lam);
        const double g = t1 * t1 + t2 * t2, sg = std::sqrt(g);
        const double phi = 1 / r - 1 / sg;
        (phi > 0 ? lo : hi) = lam;
        const double dg = -2 * (t1 * t1 / (l1 + lam) + t2 * t2 / (l2 + lam));
        const double dphi = 0.5 * dg / (g * sg);
        double next = dphi < 0 ? lam - phi / dphi : 0.5 * (lo + hi);
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        const bool done = std::abs(next - lam) <= 1e-15 * next || hi - lo <= 1e-15 * hi;
        lam = next;
        if (done)
            break;
    }
    const double v =
        lam * (l1 * d1 * d1 / (l1 + lam) + l2 * d2 * d2 / (l2 + lam)) - lam * r * r;
    // The touch point: the minimizer y_i = lambda d_i / (l_i + lambda), on the circle.
    const double y1 = lam * d1 / (l1 + lam), y2 = lam * d2 / (l2 + lam);
    double ux = f.ex * y1 - f.ey * y2 - dx, uy = f.ey * y1 + f.ex * y2 - dy;
    const double un = std::hypot(ux, uy);
    if (un > 0) {
        ux *= r / un;
        uy *= r / un;
    }
    return {std::max(0.0, v), cx + ux, cy + uy};
}

// Minimum of q over one obstacle square [xl, xh] x [yl, yh] grown by the
// disc of radius r: the union of the square widened by r, the square
// heightened by r and the discs at the corners named in `corners` (bit k:
// 0 = (xl, yl), 1 = (xh, yl), 2 = (xl, yh), 3 = (xh, yh)). Skipped when its
// bounding box cannot beat best2.
void roundedSquareMin(const TForm& f, double px, double py, double xl, double xh,
                      double yl, double yh, double r, unsigned corners, double& best2,
                      TDmax& best) {
    if (r <= 0)
        return keep(rectMin(f, px, py, xl, xh, yl, yh), best2, best);
    if (rectMin(f, px, py, xl - r, xh + r, yl - r, yh + r).q >= best2)
        return;
    keep(rectMin(f, px, py, xl - r, xh + r, yl, yh), best2, best);
    keep(rectMin(f, px, py, xl, xh, yl - r, yh + r), best2, best);
    for (unsigned k = 0; k < 4; k++) {
        if (!(corners & (1u << k)) || !(best2 > 0))
            continue;
        const double cx = k & 1 ? xh : xl, cy = k & 2 ? yh : yl;
        if (rectMin(f, px, py, cx - r, cx + r, cy - r, cy + r).q < best2)
            keep(discMin(f, px, py, cx, cy, r), best2, best);
    }
}

// Minimum of q over the outside of the map [x0, x1] x [y0, y1] (already
// shrunk by r): the union of the half-planes x <= x0, x >= x1, y <= y0,
// y >= y1. On the line x = X the minimum is at y = py - b/c (X - px), q =
// (X - px)^2 (a - b^2/c) = (X - px)^2 / Sigma_xx: the Mahalanobis distance to
// a line (alike for y).
void outsideMin(const TForm& f, double px, double py, double x0, double x1, double y0,
                double y1, double& best2, TDmax& best) {
    if (px <= x0 || px >= x1 || py <= y0 || py >= y1)
        return keep({0, px, py}, best2, best);
    for (double x : {x0, x1})
        keep({(x - px) * (x - px) / f.sxx, x, py - f.b / f.c * (x - px)}, best2, best);
    for (double y : {y0, y1})
        keep({(y - py) * (y - py) / f.syy, px - f.b / f.a * (y - py), y}, best2, best);
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
    m_left.resize(n);
    m_right.resize(n);
    m_convex.assign(n, 0);
    for (int cy = 0; cy < h; cy++) {
        const size_t row = size_t(cy) * w;
        int last = -1;
        for (int cx = 0; cx < w; cx++) {
            if (rawObstacle(cx, cy)) {
                last = cx;
                m_raw.push_back(uint32_t(row + cx));
                // A corner is convex (its disc is needed) when neither
                // neighbour across it is an obstacle: otherwise the
                // neighbour's widened or heightened square covers it.
                unsigned k = 0;
                for (unsigned c = 0; c < 4; c++) {
                    const int nx = cx + (c & 1 ? 1 : -1), ny = cy + (c & 2 ? 1 : -1);
                    if (!rawObstacle(nx, cy) && !rawObstacle(cx, ny))
                        k |= 1u << c;
                }
                m_convex[row + cx] = uint8_t(k);
            }
            m_left[row + cx] = last;
        }
        last = w;
        for (int cx = w - 1; cx >= 0; cx--) {
            if (rawObstacle(cx, cy))
                last = cx;
            m_right[row + cx] = last;
        }
    }
    m_obst.assign(n, 0);
    for (int cy = 0; cy < h; cy++)
        for (int cx = 0; cx < w; cx++)
            if (isObstacleAt(colToX(cx), rowToY(cy))) {
                m_obst[size_t(cy) * w + cx] = 1;
                m_nGrown++;
            }
}

bool CObstacleField::isObstacleAt(double x, double y) const {
    const double r = m_radius, res = resolution();
    if (rule().outside_is_obstacle && (x - xMin() <= r || m_df.xMax() - x <= r ||
                                       y - yMin() <= r || m_df.yMax() - y <= r))
        return true;
    const int cx = xToCol(std::clamp(x, xMin() - 2 * res, m_df.xMax() + 2 * res)),
              cy = yToRow(std::clamp(y, yMin() - 2 * res, m_df.yMax() + 2 * res));
    if (m_df.inside(cx, cy)) {
        // The distance field holds the distance c between cell CENTRES; every
        // square lies within res/sqrt(2) of its centre and holds the disc of
        // radius res/2 around it, so the distance from (x, y) to the nearest
        // square is in [c - o - res/sqrt(2), c + o - res/2], o = the offset of
        // (x, y) from its cell's centre. The float field: 1e-5 m of slack.
        const double c = m_df.clearance(cx, cy);
        const double o = std::hypot(x - colToX(cx), y - rowToY(cy));
        if (c - o - res * M_SQRT1_2 > r + 1e-5)
            return false;
        if (c + o - 0.5 * res < r - 1e-5)
            return true;
    }
    const int k = int(std::ceil(r / res)) + 1;
    for (int j = cy - k; j <= cy + k; j++)
        for (int i = cx - k; i <= cx + k; i++) {
            if (!m_df.inside(i, j) || !rawObstacle(i, j))
                continue;
            const double xl = xMin() + i * res, yl = yMin() + j * res;
            const double dx = std::max({xl - x, 0.0, x - xl - res}),
                         dy = std::max({yl - y, 0.0, y - yl - res});
            if (dx * dx + dy * dy <= r * r)
                return true;
        }
    return false;
}

TDmax CObstacleField::dMax(double x, double y, const Eigen::Matrix2d& cov) const {
    TForm f;
    TDmax best;
    if (!makeForm(cov, f)) {
        best.d = std::numeric_limits<double>::quiet_NaN();
        return best;
    }
    double best2 = std::numeric_limits<double>::infinity();
    const int w = m_df.sizeX(), h = m_df.sizeY();
    const double res = m_df.resolution(), xmin = m_df.xMin(), ymin = m_df.yMin(),
                 r = m_radius;
    if (m_df.rule().outside_is_obstacle)
        outsideMin(f, x, y, xmin + r, m_df.xMax() - r, ymin + r, m_df.yMax() - r, best2,
                   best);
    // A column index for any x (clamped to the map before the conversion).
    auto col = [&](double v) {
        return int(std::clamp(std::floor((v - xmin) / res), 0.0, double(w - 1)));
    };
    // A row of obstacle squares grown by r spans the band [yl - r, yh + r]: its
    // squares that can hold the minimum are those within r of the segment of
    // parabola minima x*(y') = x - b/a (y' - y), y' in the band, plus the
    // nearest obstacle on either side of them (per-row indexes).
    auto visitRow = [&](int cy) {
        const double yl = ymin + cy * res, yh = yl + res;
        double lo = x - f.b / f.a * (yl - r - y), hi = x - f.b / f.a * (yh + r - y);
        if (lo > hi)
            std::swap(lo, hi);
        const int cL = col(lo - r), cR = col(hi + r);
        const size_t row = size_t(cy) * w;
        auto cell = [&](int cx) {
            const double xl = xmin + cx * res;
            roundedSquareMin(f, x, y, xl, xl + res, yl, yh, r, m_convex[row + cx], best2,
                             best);
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
        const double yl = ymin + cy * res - r, yh = ymin + (cy + 1) * res + r;
        const double dy = y < yl ? yl - y : (y > yh ? y - yh : 0.0);
        return dy * dy / f.syy;
    };
    const int cy0 = int(std::clamp(std::floor((y - ymin) / res), 0.0, double(h - 1)));
    for (int cy = cy0; cy < h && bandBound(cy) < best2; cy++)
        visitRow(cy);
    for (int cy = cy0 - 1; cy >= 0 && bandBound(cy) < best2; cy--)
        visitRow(cy);
    best.d = std::sqrt(std::max(0.0, best2));
    return best;
}

TDmax CObstacleField::dMaxBruteForce(double x, double y,
                                     const Eigen::Matrix2d& cov) const {
    TForm f;
    TDmax best;
    if (!makeForm(cov, f)) {
        best.d = std::numeric_limits<double>::quiet_NaN();
        return best;
    }
    double best2 = std::numeric_limits<double>::infinity();
    const int w = m_df.sizeX();
    const double res = m_df.resolution(), r = m_radius;
    for (uint32_t idx : m_raw) {
        const double xl = m_df.xMin() + int(idx % uint32_t(w)) * res,
                     yl = m_df.yMin() + int(idx / uint32_t(w)) * res;
        if (r <= 0) {
            keep(rectMin(f, x, y, xl, xl + res, yl, yl + res), best2, best);
            continue;
        }
        keep(rectMin(f, x, y, xl - r, xl + res + r, yl, yl + res), best2, best);
        keep(rectMin(f, x, y, xl, xl + res, yl - r, yl + res + r), best2, best);
        for (double cx : {xl, xl + res})
            for (double cy : {yl, yl + res})
                keep(discMin(f, x, y, cx, cy, r), best2, best);
    }
    if (m_df.rule().outside_is_obstacle)
        outsideMin(f, x, y, m_df.xMin() + r, m_df.xMax() - r, m_df.yMin() + r,
                   m_df.yMax() - r, best2, best);
    best.d = std::sqrt(std::max(0.0, best2));
    return best;
}

bool CObstacleField::segmentFree(double x0, double y0, double x1, double y1) const {
    return geometry::segmentFree(
        x0, y0, x1, y1, 0.5 * resolution(),
        [this](double x, double y) { return isObstacleAt(x, y); });
}

}  // namespace risknav::risk
