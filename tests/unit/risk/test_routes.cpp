#include <risknav/geometry/polyline.h>
#include <risknav/risk/CGvgRoutes.h>

#include <gtest/gtest.h>

using namespace risknav::risk;
using mrpt::math::TPoint2D;
using risknav::geometry::polylineLength;

namespace {
mrpt::maps::COccupancyGridMap2D room(bool island, bool walls = true) {
    // 12 x 8 m room with walls; optionally a 4 x 2 m block in the middle.
    mrpt::maps::COccupancyGridMap2D g(0, 12, 0, 8, 0.05f);
    g.fill(1.0f);
    for (unsigned cy = 0; cy < g.getSizeY(); cy++)
        for (unsigned cx = 0; cx < g.getSizeX(); cx++) {
            const double x = g.idx2x(cx), y = g.idx2y(cy);
            const bool wall = walls && (x < 0.3 || x > 11.7 || y < 0.3 || y > 7.7);
            const bool block = island && x > 4 && x < 8 && y > 3 && y < 5;
            if (wall || block)
                g.setCell(cx, cy, 0.0f);
        }
    return g;
}
}  // namespace

TEST(CGvgRoutes, TwoWaysAroundAnIsland) {
    const CObstacleField f(room(true), {}, 0.25);
    const CGvgRoutes gvg(f, {});
    EXPECT_GT(gvg.skeletonCells(), 100u);
    const auto r = gvg.routes({1.5, 4}, {10.5, 4}, 5);
    ASSERT_GE(r.size(), 2u);
    // The two shortest go above and below the block, along the middle of the
    // 2.7 m gaps (y ~ 6.35 and ~ 1.65), and are about equally long.
    auto maxY = [](const std::vector<TPoint2D>& p) {
        double m = -1e9;
        for (const auto& q : p)
            m = std::max(m, q.y);
        return m;
    };
    auto minY = [](const std::vector<TPoint2D>& p) {
        double m = 1e9;
        for (const auto& q : p)
            m = std::min(m, q.y);
        return m;
    };
    const bool firstAbove = maxY(r[0]) > 5.5;
    const auto& above = firstAbove ? r[0] : r[1];
    const auto& below = firstAbove ? r[1] : r[0];
    EXPECT_NEAR(maxY(above), 6.35, 0.3);
    EXPECT_GT(minY(above), 3.0);
    EXPECT_NEAR(minY(below), 1.65, 0.3);
    EXPECT_NEAR(polylineLength(r[0]), polylineLength(r[1]), 1.0);
    for (const auto& route : r) {
        EXPECT_NEAR(route.front().x, 1.5, 1e-9);
        EXPECT_NEAR(route.back().x, 10.5, 1e-9);
        for (size_t i = 1; i < route.size(); i++)
            EXPECT_TRUE(
                f.segmentFree(route[i - 1].x, route[i - 1].y, route[i].x, route[i].y));
    }
}

TEST(CGvgRoutes, NoRouteWhenWalledOff) {
    auto g = room(false);
    for (unsigned cy = 0; cy < g.getSizeY(); cy++)
        for (unsigned cx = 118; cx < 122; cx++)
            g.setCell(cx, cy, 0.0f);  // a wall at x = 6
    const CObstacleField f(g, {}, 0.25);
    EXPECT_TRUE(CGvgRoutes(f, {}).routes({1.5, 4}, {10.5, 4}, 3).empty());
}

// Without a border wall the outside of the map is the wall (the obstacle
// rule's default): the GVG runs between the block and the map's edges.
TEST(CGvgRoutes, OpenMapHasItsEdgesAsWalls) {
    const CObstacleField f(room(true, false), {}, 0.25);
    const auto r = CGvgRoutes(f, {}).routes({1.5, 4}, {10.5, 4}, 5);
    ASSERT_GE(r.size(), 2u);
    double lo = 1e9, hi = -1e9;
    for (const auto& route : r)
        for (const auto& q : route) {
            lo = std::min(lo, q.y);
            hi = std::max(hi, q.y);
        }
    EXPECT_NEAR(hi, 6.5, 0.3);  // midway between the block (y = 5) and the edge (8)
    EXPECT_NEAR(lo, 1.5, 0.3);
}
