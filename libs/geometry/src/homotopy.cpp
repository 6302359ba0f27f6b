#include <risknav/geometry/homotopy.h>

#include <opencv2/imgproc.hpp>

using mrpt::math::TPoint2D;

namespace risknav::geometry {
bool sameHomotopy(const std::vector<TPoint2D>& a, const std::vector<TPoint2D>& b,
                  const TObstacleRaster& r) {
    std::vector<cv::Point> poly;
    for (const auto& p : a)
        poly.emplace_back(r.xToCol(p.x), r.yToRow(p.y));
    for (auto it = b.rbegin(); it != b.rend(); ++it)
        poly.emplace_back(r.xToCol(it->x), r.yToRow(it->y));
    const cv::Rect box = cv::boundingRect(poly) & cv::Rect(0, 0, r.sizeX, r.sizeY);
    if (box.area() == 0)
        return true;
    cv::Mat inside(box.height, box.width, CV_8UC1, cv::Scalar(0));
    for (auto& q : poly)
        q -= box.tl();
    cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(1));
    for (int y = 0; y < box.height; y++)
        for (int x = 0; x < box.width; x++)
            if (inside.at<uint8_t>(y, x) && r.isObstacle(x + box.x, y + box.y))
                return false;
    return true;
}

}  // namespace risknav::geometry
