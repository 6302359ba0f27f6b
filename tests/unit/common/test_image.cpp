#include <risknav/common/CMapImage.h>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

using namespace risknav::common;
using mrpt::math::TPoint2D;

namespace {
mrpt::maps::COccupancyGridMap2D emptyGrid() {
    mrpt::maps::COccupancyGridMap2D g(0, 10, 0, 5, 0.05f);  // 200 x 100 cells
    g.fill(1.0f);
    return g;
}

bool isColour(const cv::Vec3b& p, int r, int g, int b, int tol = 40) {
    return std::abs(p[2] - r) < tol && std::abs(p[1] - g) < tol &&
           std::abs(p[0] - b) < tol;
}

// An anti-aliased green line passes within 1 px of (row, col).
bool greenNear(const cv::Mat& m, double row, double col) {
    for (int dr = -1; dr <= 1; dr++)
        for (int dc = -1; dc <= 1; dc++) {
            const auto p =
                m.at<cv::Vec3b>(int(std::lround(row)) + dr, int(std::lround(col)) + dc);
            if (p[1] > p[2] + 60 && p[1] > p[0] + 60)
                return true;
        }
    return false;
}
}  // namespace

TEST(CMapImage, WorldToPixel) {
    CMapImage img(emptyGrid(), 800);                // 4 px per cell -> 80 px/m
    EXPECT_NEAR(img.pixelsPerMeter(), 80.0, 1e-4);  // MRPT stores the resolution as float
    const auto p = img.toPixel(1.0, 5.0);
    EXPECT_NEAR(p.x, 80.0, 1e-4);
    EXPECT_NEAR(p.y, 0.0, 1e-4);  // y up in the world, down in the image
    EXPECT_NEAR(img.toPixel(0, 0).y, 400.0, 1e-4);
}

TEST(CMapImage, DrawsWhereItShould) {
    auto g = emptyGrid();
    for (int cx = 0; cx < 200; cx++)
        g.setCell(cx, 0, 0.0f);  // bottom wall
    CMapImage img(g, 800);
    img.polyline({{1, 1}, {9, 1}}, {255, 0, 0}, 3);
    img.marker({5, 4}, CMapImage::TMarker::Square, {0, 0, 255}, 20, 2);
    const cv::Mat& m = img.mapArea();
    EXPECT_TRUE(
        isColour(m.at<cv::Vec3b>(320, 400), 255, 0, 0));  // on the red line y = 1 m
    EXPECT_TRUE(
        isColour(m.at<cv::Vec3b>(200, 400), 255, 255, 255));    // free space stays white
    EXPECT_TRUE(isColour(m.at<cv::Vec3b>(398, 100), 0, 0, 0));  // the wall is black
    EXPECT_TRUE(isColour(m.at<cv::Vec3b>(80 - 10, 400), 0, 0,
                         255));  // square edge 10 px above (5, 4)
}

TEST(CMapImage, EllipseAxesFollowTheCovariance) {
    CMapImage img(emptyGrid(), 800);
    mrpt::math::CMatrixFixed<double, 2, 2> cov;
    cov(0, 0) = 1.0;  // sigma_x = 1 m, sigma_y = 0.5 m
    cov(1, 1) = 0.25;
    cov(0, 1) = cov(1, 0) = 0;
    img.ellipse({5, 2.5}, cov, 1.0, {0, 200, 0}, 1);
    const cv::Mat& m = img.mapArea();
    const auto c = img.toPixel(5, 2.5);
    // Extreme points at +-1 m in x (80 px), +-0.5 m in y (40 px); nothing inside.
    EXPECT_TRUE(greenNear(m, c.y, c.x + 80));
    EXPECT_TRUE(greenNear(m, c.y, c.x - 80));
    EXPECT_TRUE(greenNear(m, c.y - 40, c.x));
    EXPECT_TRUE(greenNear(m, c.y + 40, c.x));
    EXPECT_FALSE(greenNear(m, c.y, c.x + 40));
    EXPECT_FALSE(greenNear(m, c.y - 60, c.x));

    // Correlated: the major axis along the world's +45 deg diagonal (up-right
    // in the image): sigma^2 = 1 along it, 0.25 across it.
    CMapImage img2(emptyGrid(), 800);
    cov(0, 0) = cov(1, 1) = 0.625;
    cov(0, 1) = cov(1, 0) = 0.375;
    img2.ellipse({5, 2.5}, cov, 1.0, {0, 200, 0}, 1);
    const double d = 80 / std::sqrt(2.0);
    EXPECT_TRUE(greenNear(img2.mapArea(), c.y - d, c.x + d));
    EXPECT_TRUE(greenNear(img2.mapArea(), c.y + d, c.x - d));
    EXPECT_FALSE(greenNear(img2.mapArea(), c.y + d, c.x + d));
}

TEST(CMapImage, HeatOverlayAndColourBar) {
    auto g = emptyGrid();
    std::vector<float> v(200 * 100, 0.f);
    for (int cx = 100; cx < 200; cx++)
        for (int cy = 0; cy < 100; cy++)
            v[cy * 200 + cx] = 1.0f;
    CMapImage img(g, 800);
    img.heatOverlay(v, 0.f, 1.f, "level [-]", 1.0, 0.5f);
    const cv::Mat& m = img.mapArea();
    EXPECT_TRUE(
        isColour(m.at<cv::Vec3b>(200, 100), 255, 255, 255));  // below showFrom: untouched
    EXPECT_TRUE(
        isColour(m.at<cv::Vec3b>(200, 700), 128, 0, 0, 60));  // jet maximum: dark red
    const cv::Mat full = img.compose();
    EXPECT_GT(full.cols, m.cols);  // room for the colour bar
}

TEST(CMapImage, SavesAPngWithTitleLegendAndScaleBar) {
    CMapImage img(emptyGrid(), 800);
    img.setTitle("title");
    img.legendLine("path", {0, 0, 255});
    img.legendMarker("event", CMapImage::TMarker::Cross, {255, 0, 0});
    const std::string f = risknav::test::freshDir("img") + "/a.png";
    img.save(f);
    const cv::Mat back = cv::imread(f);
    ASSERT_FALSE(back.empty());
    EXPECT_EQ(back.cols, std::max(800, 520));
    EXPECT_GT(back.rows, 400);  // map + title + legend
    EXPECT_THROW(img.save("/nonexistent/dir/a.png"), std::runtime_error);
}

TEST(CMapImage, NiceScaleBarLengths) {
    EXPECT_DOUBLE_EQ(CMapImage::niceLength(7.3), 5.0);
    EXPECT_DOUBLE_EQ(CMapImage::niceLength(2.4), 2.0);
    EXPECT_DOUBLE_EQ(CMapImage::niceLength(0.13), 0.1);
    EXPECT_DOUBLE_EQ(CMapImage::niceLength(1.0), 1.0);
}
