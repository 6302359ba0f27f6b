#include <risknav/risk/CGvgRoutes.h>
#include <risknav/risk/k_shortest_paths.h>
#include <risknav/risk/path_risk.h>

#include <gtest/gtest.h>

#include <functional>
#include <random>

using namespace risknav::risk;
using mrpt::math::TPoint2D;

namespace {
// Every simple path (as edge lists) by depth-first search: the reference.
std::vector<TGraphPath> allSimplePaths(size_t n, const std::vector<TGraphEdge>& edges,
                                       size_t s, size_t t) {
    std::vector<TGraphPath> out;
    std::vector<bool> onPath(n, false);
    TGraphPath cur;
    std::function<void(size_t)> dfs = [&](size_t u) {
        if (u == t) {
            out.push_back(cur);
            return;
        }
        onPath[u] = true;
        for (size_t e = 0; e < edges.size(); e++) {
            if (edges[e].a != u && edges[e].b != u)
                continue;
            const size_t v = edges[e].a == u ? edges[e].b : edges[e].a;
            if (onPath[v])
                continue;
            cur.edges.push_back(e);
            cur.length += edges[e].length;
            dfs(v);
            cur.edges.pop_back();
            cur.length -= edges[e].length;
        }
        onPath[u] = false;
    };
    dfs(s);
    std::sort(out.begin(), out.end(), [](const TGraphPath& a, const TGraphPath& b) {
        return a.length < b.length;
    });
    return out;
}
}  // namespace

TEST(KShortestPaths, MatchesExhaustiveEnumerationOnRandomMultigraphs) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> len(1, 10);
    for (int g = 0; g < 30; g++) {
        const size_t n = 6 + g % 4;
        std::vector<TGraphEdge> edges;
        std::uniform_int_distribution<size_t> node(0, n - 1);
        for (size_t e = 0; e < 2 * n; e++) {
            const size_t a = node(rng), b = node(rng);
            if (a != b)
                edges.push_back(
                    {a, b, std::round(len(rng) * 8) / 8 + 1e-3 * e});  // distinct lengths
        }
        const auto ref = allSimplePaths(n, edges, 0, n - 1);
        const auto yen = kShortestPaths(n, edges, 0, n - 1, 6);
        ASSERT_EQ(yen.size(), std::min<size_t>(6, ref.size())) << "graph " << g;
        for (size_t i = 0; i < yen.size(); i++) {
            EXPECT_NEAR(yen[i].length, ref[i].length, 1e-9)
                << "graph " << g << " path " << i;
            EXPECT_EQ(yen[i].edges, ref[i].edges) << "graph " << g << " path " << i;
            EXPECT_EQ(yen[i].nodes.front(), 0u);
            EXPECT_EQ(yen[i].nodes.back(), n - 1);
        }
    }
}

TEST(KShortestPaths, Unreachable) {
    EXPECT_TRUE(kShortestPaths(4, {{0, 1, 1.0}, {2, 3, 1.0}}, 0, 3, 3).empty());
}

namespace {
mrpt::maps::COccupancyGridMap2D room(bool island) {
    // 12 x 8 m room with walls; optionally a 4 x 2 m block in the middle.
    mrpt::maps::COccupancyGridMap2D g(0, 12, 0, 8, 0.05f);
    g.fill(1.0f);
    for (unsigned cy = 0; cy < g.getSizeY(); cy++)
        for (unsigned cx = 0; cx < g.getSizeX(); cx++) {
            const double x = g.idx2x(cx), y = g.idx2y(cy);
            const bool wall = x < 0.3 || x > 11.7 || y < 0.3 || y > 7.7;
            const bool block = island && x > 4 && x < 8 && y > 3 && y < 5;
            if (wall || block)
                g.setCell(cx, cy, 0.0f);
        }
    return g;
}
}  // namespace

TEST(CGvgRoutes, TwoWaysAroundAnIsland) {
    CObstacleField::TOptions fo;
    fo.robot_radius = 0.25;
    const CObstacleField f(room(true), fo);
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
    CObstacleField::TOptions fo;
    fo.robot_radius = 0.25;
    const CObstacleField f(g, fo);
    EXPECT_TRUE(CGvgRoutes(f, {}).routes({1.5, 4}, {10.5, 4}, 3).empty());
}
