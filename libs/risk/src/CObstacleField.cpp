#include <risknav/geometry/polyline.h>
#include <risknav/risk/CObstacleField.h>

#include <opencv2/imgproc.hpp>

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
}  // namespace

CObstacleField::CObstacleField(const mrpt::maps::COccupancyGridMap2D& g,
                               const TOptions& o)
    : m_opts(o),
      m_w(int(g.getSizeX())),
      m_h(int(g.getSizeY())),
      m_xmin(g.getXMin()),
      m_ymin(g.getYMin()),
      m_res(g.getResolution()) {
    const size_t n = size_t(m_w) * m_h;
    m_raw.assign(n, 0);
    cv::Mat freeMask(m_h, m_w, CV_8UC1);
    for (int cy = 0; cy < m_h; cy++)
        for (int cx = 0; cx < m_w; cx++) {
            const double occ = 1.0 - g.getCell(cx, cy);
            const bool obst = occ >= o.occupied_threshold ||
                              (occ > o.free_threshold && o.unknown_is_obstacle);
            m_raw[size_t(cy) * m_w + cx] = obst;
            freeMask.at<uint8_t>(cy, cx) = obst ? 0 : 255;
        }
    // Distance from each cell centre to the nearest raw obstacle cell centre.
    cv::Mat dist;
    cv::distanceTransform(freeMask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    m_clearance.resize(n);
    m_obst.assign(n, 0);
    for (int cy = 0; cy < m_h; cy++)
        for (int cx = 0; cx < m_w; cx++) {
            const float d = dist.at<float>(cy, cx) * float(m_res);
            m_clearance[size_t(cy) * m_w + cx] = d;
            // Grown by the robot radius (a hair of slack for float rounding).
            if (d <= o.robot_radius + 1e-6) {
                m_obst[size_t(cy) * m_w + cx] = 1;
                m_cells.push_back(uint32_t(size_t(cy) * m_w + cx));
            }
        }
    m_left.resize(n);
    m_right.resize(n);
    for (int cy = 0; cy < m_h; cy++) {
        const size_t row = size_t(cy) * m_w;
        int last = -1;
        for (int cx = 0; cx < m_w; cx++) {
            if (m_obst[row + cx])
                last = cx;
            m_left[row + cx] = last;
        }
        last = m_w;
        for (int cx = m_w - 1; cx >= 0; cx--) {
            if (m_obst[row + cx])
                last = cx;
            m_right[row + cx] = last;
        }
    }
}

namespace {
// Minimum of q(dx, dy) = a dx^2 + 2 b dx dy + c dy^2 over the square
// [xl, xh] x [yl, yh] (world coordinates, robot at (px, py)): 0 if the robot is
// inside; else the minimum of the convex q lies on the boundary, and on each
// edge it is the 1-D minimum clamped to the edge.
void squareMin(double a, double b, double c, double px, double py, double xl, double xh,
               double yl, double yh, double& best2, TDmax& best) {
    if (px >= xl && px <= xh && py >= yl && py <= yh) {
        if (best2 > 0) {
            best2 = 0;
            best.touchX = px;
            best.touchY = py;
        }
        return;
    }
    auto consider = [&](double x, double y) {
        const double dx = x - px, dy = y - py;
        const double q = a * dx * dx + 2 * b * dx * dy + c * dy * dy;
        if (q < best2) {
            best2 = q;
            best.touchX = x;
            best.touchY = y;
        }
    };
    for (double y : {yl, yh})
        consider(std::clamp(px - b / a * (y - py), xl, xh), y);
    for (double x : {xl, xh})
        consider(x, std::clamp(py - b / c * (x - px), yl, yh));
}
}  // namespace

TDmax CObstacleField::dMax(double x, double y, const Eigen::Matrix2d& cov) const {
    double a, b, c, syy;
    inverse2(cov, a, b, c, syy);
    TDmax best;
    double best2 = std::numeric_limits<double>::infinity();
    // A row band: its obstacle cells that can hold the minimum are those under
    // the segment of parabola minima x*(y) = x - b/a (y - y), y in the band,
    // plus the nearest obstacle on either side of it (per-row indexes).
    auto visitRow = [&](int cy) {
        const double yl = m_ymin + cy * m_res, yh = yl + m_res;
        double lo = x - b / a * (yl - y), hi = x - b / a * (yh - y);
        if (lo > hi)
            std::swap(lo, hi);
        const int cL = std::clamp(xToCol(lo), 0, m_w - 1),
                  cR = std::clamp(xToCol(hi), 0, m_w - 1);
        const size_t row = size_t(cy) * m_w;
        auto cell = [&](int cx) {
            const double xl = m_xmin + cx * m_res;
            squareMin(a, b, c, x, y, xl, xl + m_res, yl, yh, best2, best);
        };
        if (m_left[row + cL] >= 0)
            cell(m_left[row + cL]);
        for (int cx = m_right[row + cL]; cx <= cR && cx < m_w;
             cx = cx + 1 < m_w ? m_right[row + cx + 1] : m_w)
            cell(cx);
        if (m_right[row + cR] < m_w)
            cell(m_right[row + cR]);
    };
    // Every point of a band is at least its vertical gap dy away, and
    // q >= dy^2 / Sigma_yy: visit bands outwards while they can still win.
    auto bandBound = [&](int cy) {
        const double yl = m_ymin + cy * m_res, yh = yl + m_res;
        const double dy = y < yl ? yl - y : (y > yh ? y - yh : 0.0);
        return dy * dy / syy;
    };
    const int cy0 = std::clamp(yToRow(y), 0, m_h - 1);
    for (int cy = cy0; cy < m_h && bandBound(cy) < best2; cy++)
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
    for (uint32_t idx : m_cells) {
        const int cx = int(idx % uint32_t(m_w)), cy = int(idx / uint32_t(m_w));
        const double xl = m_xmin + cx * m_res, yl = m_ymin + cy * m_res;
        squareMin(a, b, c, x, y, xl, xl + m_res, yl, yl + m_res, best2, best);
    }
    best.d = std::sqrt(std::max(0.0, best2));
    return best;
}

bool CObstacleField::segmentFree(double x0, double y0, double x1, double y1) const {
    return geometry::segmentFree(x0, y0, x1, y1, 0.5 * m_res, [this](double x, double y) {
        return isObstacleAt(x, y);
    });
}

double CObstacleField::clearance(double x, double y) const {
    const int cx = xToCol(x), cy = yToRow(y);
    if (cx < 0 || cy < 0 || cx >= m_w || cy >= m_h)
        return 0.0;
    return m_clearance[size_t(cy) * m_w + cx];
}

}  // namespace risknav::risk
