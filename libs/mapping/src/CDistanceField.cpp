#include <risknav/mapping/CDistanceField.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <limits>
#include <unordered_map>

namespace risknav::mapping {
namespace {
// 255 = free, 0 = obstacle, with one cell of padding holding the outside ring
// (an obstacle or not by the rule): what OpenCV's transforms take.
cv::Mat paddedFreeMask(const std::vector<uint8_t>& obst, int w, int h,
                       bool outsideIsObstacle) {
    cv::Mat m(h + 2, w + 2, CV_8UC1, cv::Scalar(outsideIsObstacle ? 0 : 255));
    for (int cy = 0; cy < h; cy++)
        for (int cx = 0; cx < w; cx++)
            m.at<uint8_t>(cy + 1, cx + 1) = obst[size_t(cy) * w + cx] ? 0 : 255;
    return m;
}
}  // namespace

CDistanceField::CDistanceField(const mrpt::maps::COccupancyGridMap2D& g,
                               const TObstacleRule& rule)
    : m_rule(rule),
      m_w(int(g.getSizeX())),
      m_h(int(g.getSizeY())),
      m_xmin(g.getXMin()),
      m_ymin(g.getYMin()),
      m_res(g.getResolution()) {
    m_obst.assign(size_t(m_w) * m_h, 0);
    m_dist.assign(m_obst.size(), std::numeric_limits<float>::infinity());
    for (int cy = 0; cy < m_h; cy++)
        for (int cx = 0; cx < m_w; cx++) {
            const bool o = rule.isObstacle(g.getCell(cx, cy));
            m_obst[size_t(cy) * m_w + cx] = o;
            m_nObst += o;
        }
    if (m_nObst > 0 && m_nObst < m_obst.size()) {
        // Depth inside the obstacles: the same transform on the inverted mask
        // (the outside ring does not count as free space).
        cv::Mat inv = 255 - paddedFreeMask(m_obst, m_w, m_h, true), d;
        cv::distanceTransform(inv, d, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
        m_depth.assign(m_obst.size(), 0.f);
        for (int cy = 0; cy < m_h; cy++)
            for (int cx = 0; cx < m_w; cx++)
                m_depth[size_t(cy) * m_w + cx] =
                    d.at<float>(cy + 1, cx + 1) * float(m_res);
    }
    if (m_nObst == 0 && !rule.outside_is_obstacle)
        return;  // nothing to measure against: +inf everywhere
    cv::Mat dist;
    cv::distanceTransform(paddedFreeMask(m_obst, m_w, m_h, rule.outside_is_obstacle),
                          dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    for (int cy = 0; cy < m_h; cy++)
        for (int cx = 0; cx < m_w; cx++)
            m_dist[size_t(cy) * m_w + cx] = dist.at<float>(cy + 1, cx + 1) * float(m_res);
}

TNearestObstacles CDistanceField::nearestObstacles() const {
    TNearestObstacles n;
    n.sizeX = m_w;
    n.sizeY = m_h;
    n.any = m_nObst > 0 || m_rule.outside_is_obstacle;
    if (!n.any || m_w == 0 || m_h == 0)
        return n;
    const cv::Mat freeMask = paddedFreeMask(m_obst, m_w, m_h, m_rule.outside_is_obstacle);
    cv::Mat dist, labels;
    cv::distanceTransform(freeMask, dist, labels, cv::DIST_L2, cv::DIST_MASK_5,
                          cv::DIST_LABEL_PIXEL);
    // Label -> the obstacle cell it names (padded coordinates - 1 = cell indices).
    std::unordered_map<int, std::pair<int32_t, int32_t>> where;
    for (int py = 0; py < freeMask.rows; py++)
        for (int px = 0; px < freeMask.cols; px++)
            if (!freeMask.at<uint8_t>(py, px))
                where[labels.at<int>(py, px)] = {px - 1, py - 1};
    const size_t cells = size_t(m_w) * m_h;
    n.obstX.resize(cells);
    n.obstY.resize(cells);
    n.distCells.resize(cells);
    for (int cy = 0; cy < m_h; cy++)
        for (int cx = 0; cx < m_w; cx++) {
            const auto& [ox, oy] = where.at(labels.at<int>(cy + 1, cx + 1));
            n.obstX[n.index(cx, cy)] = ox;
            n.obstY[n.index(cx, cy)] = oy;
            n.distCells[n.index(cx, cy)] = dist.at<float>(cy + 1, cx + 1);
        }
    return n;
}

double CDistanceField::pointClearance(double x, double y, double reach) const {
    const double coarse = clearanceAt(x, y);
    if (!(coarse <= reach + 2 * m_res))
        return coarse;
    const int r = int(std::ceil((reach + 2 * m_res) / m_res));
    const int ci = x2idx(x), cj = y2idx(y);
    double best = std::numeric_limits<double>::infinity();
    for (int cy = cj - r; cy <= cj + r; cy++)
        for (int cx = ci - r; cx <= ci + r; cx++) {
            if (!isObstacle(cx, cy))
                continue;
            // point to the square [x0, x0 + res] x [y0, y0 + res]
            const double x0 = m_xmin + cx * m_res, y0 = m_ymin + cy * m_res;
            const double dx = std::max({x0 - x, 0.0, x - (x0 + m_res)});
            const double dy = std::max({y0 - y, 0.0, y - (y0 + m_res)});
            best = std::min(best, std::hypot(dx, dy));
        }
    return std::min(best, coarse);
}

double CDistanceField::clearance(int cx, int cy) const {
    if (m_w == 0 || m_h == 0)
        return 0.0;
    if (!inside(cx, cy)) {
        if (m_rule.outside_is_obstacle)
            return 0.0;
        cx = std::clamp(cx, 0, m_w - 1);
        cy = std::clamp(cy, 0, m_h - 1);
    }
    return m_dist[size_t(cy) * m_w + cx];
}

}  // namespace risknav::mapping
