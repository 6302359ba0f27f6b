#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/afraid/afraid_zones.h>
#include <risknav/common/stopping.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace risknav::afraid {
std::vector<TAfraidZone> findZones(const std::vector<float>& level, const CAfraidGrid& g,
                                   double threshold, double approach) {
    const int sx = g.sizeX(), sy = g.sizeY();
    cv::Mat mask(sy, sx, CV_8UC1), labels;
    for (int cy = 0; cy < sy; cy++)
        for (int cx = 0; cx < sx; cx++)
            mask.at<uint8_t>(cy, cx) = level[size_t(cy) * sx + cx] > threshold ? 255 : 0;

    const int n = cv::connectedComponents(mask, labels, 8, CV_32S);
    std::vector<TAfraidZone> z(size_t(std::max(0, n - 1)));
    for (size_t i = 0; i < z.size(); i++) {
        z[i].id = int(i) + 1;
        z[i].xMin = z[i].yMin = 1e18;
        z[i].xMax = z[i].yMax = -1e18;
    }
    const double r = g.resolution();
    for (int cy = 0; cy < sy; cy++)
        for (int cx = 0; cx < sx; cx++) {
            const int l = labels.at<int>(cy, cx);
            if (l <= 0)
                continue;
            auto& zz = z[size_t(l - 1)];
            const size_t k = size_t(cy) * sx + cx;
            zz.cells++;
            zz.mask.push_back(int(k));
            zz.peak = std::max(zz.peak, double(level[k]));
            zz.robotEvents += g.robotEvents()[k];
            zz.obstacleEvents += g.obstacleEvents()[k];
            zz.xMin = std::min(zz.xMin, g.colToX(cx) - r / 2);
            zz.xMax = std::max(zz.xMax, g.colToX(cx) + r / 2);
            zz.yMin = std::min(zz.yMin, g.rowToY(cy) - r / 2);
            zz.yMax = std::max(zz.yMax, g.rowToY(cy) + r / 2);
        }
    // Each zone's slow region: its cells dilated by a disc of `approach`, in
    // a window around the zone only.
    const int grow = std::max(0, int(std::lround(approach / r)));
    const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                                   cv::Size(2 * grow + 1, 2 * grow + 1));
    for (auto& zz : z) {
        zz.area = zz.cells * r * r;
        int c0 = sx, c1 = -1, r0 = sy, r1 = -1;
        for (int k : zz.mask) {
            c0 = std::min(c0, k % sx);
            c1 = std::max(c1, k % sx);
            r0 = std::min(r0, k / sx);
            r1 = std::max(r1, k / sx);
        }
        const int wc0 = std::max(0, c0 - grow), wc1 = std::min(sx - 1, c1 + grow);
        const int wr0 = std::max(0, r0 - grow), wr1 = std::min(sy - 1, r1 + grow);
        cv::Mat win(wr1 - wr0 + 1, wc1 - wc0 + 1, CV_8UC1, cv::Scalar(0)), grown;
        for (int k : zz.mask)
            win.at<uint8_t>(k / sx - wr0, k % sx - wc0) = 255;
        cv::dilate(win, grown, disc);
        zz.slowXMin = zz.slowYMin = 1e18;
        zz.slowXMax = zz.slowYMax = -1e18;
        for (int wy = 0; wy < grown.rows; wy++)
            for (int wx = 0; wx < grown.cols; wx++)
                if (grown.at<uint8_t>(wy, wx)) {
                    const int cx = wx + wc0, cy = wy + wr0;
                    zz.slowMask.push_back(cy * sx + cx);
                    zz.slowXMin = std::min(zz.slowXMin, g.colToX(cx) - r / 2);
                    zz.slowXMax = std::max(zz.slowXMax, g.colToX(cx) + r / 2);
                    zz.slowYMin = std::min(zz.slowYMin, g.rowToY(cy) - r / 2);
                    zz.slowYMax = std::max(zz.slowYMax, g.rowToY(cy) + r / 2);
                }
    }
    return z;
}

double afraidSpeedLimit(const std::function<double(double, double)>& level,
                        const std::vector<mrpt::math::TPoint2D>& path, double vBehaviour,
                        double vMax, double vSafe, double threshold, double tDelay,
                        double decel, double step) {
    const double look = common::stoppingDistance(vMax, tDelay, decel);
    double vAfraid = vMax, s = 0;
    if (!path.empty() && level(path[0].x, path[0].y) > threshold)
        vAfraid = vSafe;
    for (size_t i = 1; i < path.size() && s <= look && vAfraid == vMax; i++) {
        const double L = std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
        for (double u = step; u <= L + 1e-9 && s + u <= look + 1e-9; u += step) {
            const double f = std::min(1.0, u / L);
            if (level(path[i - 1].x + f * (path[i].x - path[i - 1].x),
                      path[i - 1].y + f * (path[i].y - path[i - 1].y)) > threshold) {
                vAfraid = vSafe;
                break;
            }
        }
        s += L;
    }
    return std::min(vBehaviour, vAfraid);
}

}  // namespace risknav::afraid
