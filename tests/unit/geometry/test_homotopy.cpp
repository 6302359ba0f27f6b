// Homotopy of routes in risknav::geometry.
#include <risknav/geometry/homotopy.h>

#include <gtest/gtest.h>

using namespace risknav::geometry;
using mrpt::math::TPoint2D;

namespace {
// A 12 x 8 m raster (0.05 m cells) with a 4 x 2 m island in the middle
// (x in (4, 8), y in (3, 5)), or without it.
TObstacleRaster room(bool island) {
    TObstacleRaster r;
    r.sizeX = 240;
    r.sizeY = 160;
    r.resolution = 0.05;
    r.isObstacle = [island, res = r.resolution](int cx, int cy) {
        const double x = (cx + 0.5) * res, y = (cy + 0.5) * res;
        return island && x > 4 && x < 8 && y > 3 && y < 5;
    };
    return r;
}
const std::vector<TPoint2D> kAbove = {{1.5, 4}, {3, 6.3}, {9, 6.3}, {10.5, 4}};
const std::vector<TPoint2D> kAboveHigh = {{1.5, 4}, {2, 7}, {6, 7.5}, {10, 7}, {10.5, 4}};
const std::vector<TPoint2D> kBelow = {{1.5, 4}, {3, 1.7}, {9, 1.7}, {10.5, 4}};
}  // namespace

TEST(SameHomotopy, TwoRoutesAroundAnIslandAreDistinct) {
    const auto r = room(true);
    EXPECT_FALSE(sameHomotopy(kAbove, kBelow, r));
    EXPECT_FALSE(sameHomotopy(kBelow, kAbove, r));
    EXPECT_FALSE(sameHomotopy(kAboveHigh, kBelow, r));
}

TEST(SameHomotopy, TwoRoutesOnTheSameSideAreTheSame) {
    const auto r = room(true);
    EXPECT_TRUE(sameHomotopy(kAbove, kAboveHigh, r));
    EXPECT_TRUE(sameHomotopy(kAboveHigh, kAbove, r));
    EXPECT_TRUE(sameHomotopy(kAbove, kAbove, r));
    const std::vector<TPoint2D> belowLow = {{1.5, 4}, {2, 0.5}, {10, 0.5}, {10.5, 4}};
    EXPECT_TRUE(sameHomotopy(kBelow, belowLow, r));
}

TEST(SameHomotopy, WithoutTheIslandEveryRouteIsTheSame) {
    EXPECT_TRUE(sameHomotopy(kAbove, kBelow, room(false)));
}

TEST(SameHomotopy, OffsetRasterAndLoopsOutsideIt) {
    // The same island on a raster whose origin is at (-2, -1).
    TObstacleRaster r = room(true);
    r.xMin = -2;
    r.yMin = -1;
    auto shift = [](std::vector<TPoint2D> p) {
        for (auto& q : p) {
            q.x -= 2;
            q.y -= 1;
        }
        return p;
    };
    EXPECT_FALSE(sameHomotopy(shift(kAbove), shift(kBelow), r));
    EXPECT_TRUE(sameHomotopy(shift(kAbove), shift(kAboveHigh), r));
    // A loop entirely outside the raster encloses nothing.
    const std::vector<TPoint2D> a = {{20, 20}, {21, 25}, {22, 20}};
    const std::vector<TPoint2D> b = {{20, 20}, {21, 15}, {22, 20}};
    EXPECT_TRUE(sameHomotopy(a, b, r));
}
