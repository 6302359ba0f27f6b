#include <risknav/mapping/CDistanceField.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <limits>

namespace risknav::mapping {
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
    // One cell of padding holds the outside ring (an obstacle or not).
    const int pad = 1;
    cv::Mat freeMask(m_h + 2 * pad, m_w + 2 * pad, CV_8UC1,
                     cv::Scalar(rule.outside_is_obstacle ? 0 : 255));
    for (int cy = 0; cy < m_h; cy++)
        for (int cx = 0; cx < m_w; cx++) {
            const bool o = rule.isObstacle(g.getCell(cx, cy));
            m_obst[size_t(cy) * m_w + cx] = o;
            m_nObst += o;
            freeMask.at<uint8_t>(cy + pad, cx + pad) = o ? 0 : 255;
        }
    if (m_nObst == 0 && !rule.outside_is_obstacle)
        return;  // nothing to measure against: +inf everywhere
    cv::Mat dist;
    cv::distanceTransform(freeMask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    for (int cy = 0; cy < m_h; cy++)
        for (int cx = 0; cx < m_w; cx++)
            m_dist[size_t(cy) * m_w + cx] =
                dist.at<float>(cy + pad, cx + pad) * float(m_res);
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
