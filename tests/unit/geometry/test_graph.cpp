// Graph algorithms of risknav::geometry: Yen's k shortest loopless paths and
// Dijkstra, both against exhaustive enumeration of the simple paths.
#include <risknav/geometry/graph.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

using namespace risknav::geometry;

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
            if (edges[e].a != u && (edges[e].b != u || edges[e].directed))
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

TEST(KShortestPaths, DirectedEdgesMatchExhaustiveEnumeration) {
    // Directed edges (the viewpoint planner's tangent graph) are followed
    // a -> b only; mixed with undirected ones.
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> len(1, 10);
    std::bernoulli_distribution directed(0.7);
    int nonEmpty = 0;
    for (int g = 0; g < 40; g++) {
        const size_t n = 6 + g % 4;
        std::vector<TGraphEdge> edges;
        std::uniform_int_distribution<size_t> node(0, n - 1);
        for (size_t e = 0; e < 3 * n; e++) {
            const size_t a = node(rng), b = node(rng);
            if (a != b)
                edges.push_back(
                    {a, b, std::round(len(rng) * 8) / 8 + 1e-3 * e, directed(rng)});
        }
        const auto ref = allSimplePaths(n, edges, 0, n - 1);
        const auto yen = kShortestPaths(n, edges, 0, n - 1, 6);
        ASSERT_EQ(yen.size(), std::min<size_t>(6, ref.size())) << "graph " << g;
        nonEmpty += !yen.empty();
        for (size_t i = 0; i < yen.size(); i++) {
            EXPECT_NEAR(yen[i].length, ref[i].length, 1e-9) << "graph " << g;
            EXPECT_EQ(yen[i].edges, ref[i].edges) << "graph " << g << " path " << i;
            for (size_t k = 0; k < yen[i].edges.size(); k++) {
                const auto& e = edges[yen[i].edges[k]];
                if (e.directed) {
                    EXPECT_EQ(e.a, yen[i].nodes[k]) << "against the edge's direction";
                }
            }
        }
    }
    EXPECT_GT(nonEmpty, 20);
}

TEST(KShortestPaths, AStarHeuristicGivesTheSameLengths) {
    // Random points in the plane, edges between near ones (lengths = the
    // distance), the straight line to the target as the heuristic.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0, 10);
    std::bernoulli_distribution directed(0.5);
    for (int g = 0; g < 30; g++) {
        const size_t n = 40;
        std::vector<double> x(n), y(n);
        for (size_t i = 0; i < n; i++) {
            x[i] = u(rng);
            y[i] = u(rng);
        }
        std::vector<TGraphEdge> edges;
        for (size_t i = 0; i < n; i++)
            for (size_t j = 0; j < n; j++)
                if (i != j && std::hypot(x[i] - x[j], y[i] - y[j]) < 2.5 &&
                    (i < j || directed(rng)))
                    edges.push_back({i, j, std::hypot(x[i] - x[j], y[i] - y[j]), i > j});
        std::vector<double> h(n);
        for (size_t i = 0; i < n; i++)
            h[i] = std::hypot(x[i] - x[n - 1], y[i] - y[n - 1]);
        const auto plain = kShortestPaths(n, edges, 0, n - 1, 8);
        const auto astar = kShortestPaths(n, edges, 0, n - 1, 8, h);
        ASSERT_EQ(plain.size(), astar.size()) << "graph " << g;
        for (size_t i = 0; i < plain.size(); i++)
            EXPECT_NEAR(plain[i].length, astar[i].length, 1e-9)
                << "graph " << g << " path " << i;
    }
}

TEST(KShortestPaths, Unreachable) {
    EXPECT_TRUE(kShortestPaths(4, {{0, 1, 1.0}, {2, 3, 1.0}}, 0, 3, 3).empty());
}

namespace {
// Checks that p is a walk source -> target along non-removed edges and nodes
// whose length is the sum of its edges'.
void expectValidPath(const TGraphPath& p, const std::vector<TGraphEdge>& edges, size_t s,
                     size_t t, const std::vector<bool>& er, const std::vector<bool>& nr,
                     int g) {
    ASSERT_EQ(p.nodes.size(), p.edges.size() + 1) << "graph " << g;
    EXPECT_EQ(p.nodes.front(), s) << "graph " << g;
    EXPECT_EQ(p.nodes.back(), t) << "graph " << g;
    double L = 0;
    for (size_t i = 0; i < p.edges.size(); i++) {
        const TGraphEdge& e = edges[p.edges[i]];
        EXPECT_FALSE(er[p.edges[i]]) << "graph " << g;
        const bool fwd = e.a == p.nodes[i] && e.b == p.nodes[i + 1];
        const bool bwd = e.b == p.nodes[i] && e.a == p.nodes[i + 1];
        EXPECT_TRUE(fwd || bwd) << "graph " << g << " step " << i;
        L += e.length;
    }
    for (size_t v : p.nodes)
        EXPECT_FALSE(nr[v]) << "graph " << g;
    EXPECT_NEAR(p.length, L, 1e-9) << "graph " << g;
}
}  // namespace

TEST(ShortestPath, MatchesBruteForceOnRandomGraphsWithRemovals) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> len(0.5, 10);
    std::bernoulli_distribution removeEdge(0.15), removeNode(0.1);
    int reachable = 0, unreachable = 0;
    for (int g = 0; g < 200; g++) {
        const size_t n = 2 + size_t(g % 7);
        std::uniform_int_distribution<size_t> node(0, n - 1);
        std::vector<TGraphEdge> edges;
        for (size_t e = 0; e < 2 * n; e++)
            edges.push_back({node(rng), node(rng), len(rng)});  // self-loops allowed
        std::vector<bool> er(edges.size()), nr(n);
        for (size_t e = 0; e < edges.size(); e++)
            er[e] = removeEdge(rng);
        for (size_t v = 1; v + 1 < n; v++)
            nr[v] = removeNode(rng);
        const size_t s = 0, t = n - 1;
        // Brute force: the shortest of all simple paths of the graph without
        // the removed edges and nodes.
        std::vector<TGraphEdge> kept;
        for (size_t e = 0; e < edges.size(); e++)
            if (!er[e] && !nr[edges[e].a] && !nr[edges[e].b])
                kept.push_back(edges[e]);
        const auto all = allSimplePaths(n, kept, s, t);
        const TGraphPath p = shortestPath(n, edges, s, t, er, nr);
        if (all.empty()) {
            EXPECT_TRUE(p.nodes.empty()) << "graph " << g;
            EXPECT_TRUE(p.edges.empty()) << "graph " << g;
            unreachable++;
            continue;
        }
        reachable++;
        EXPECT_NEAR(p.length, all.front().length, 1e-9) << "graph " << g;
        expectValidPath(p, edges, s, t, er, nr, g);
    }
    // Both outcomes were exercised.
    EXPECT_GT(reachable, 50);
    EXPECT_GT(unreachable, 5);
}

TEST(ShortestPath, WithoutMasksEqualsEmptyMasks) {
    const std::vector<TGraphEdge> edges = {
        {0, 1, 1.0}, {1, 2, 1.0}, {0, 2, 2.5}, {0, 2, 1.9}};
    const TGraphPath p = shortestPath(3, edges, 0, 2);
    EXPECT_EQ(p.edges, (std::vector<size_t>{3}));  // the shorter parallel edge
    EXPECT_EQ(p.nodes, (std::vector<size_t>{0, 2}));
    EXPECT_DOUBLE_EQ(p.length, 1.9);
    const TGraphPath q = shortestPath(3, edges, 0, 0);
    EXPECT_EQ(q.nodes, (std::vector<size_t>{0}));
    EXPECT_TRUE(q.edges.empty());
    EXPECT_EQ(q.length, 0.0);
}

TEST(ShortestPath, RemovedSourceOrTargetIsUnreachable) {
    const std::vector<TGraphEdge> edges = {{0, 1, 1.0}};
    EXPECT_TRUE(shortestPath(2, edges, 0, 1, {false}, {true, false}).nodes.empty());
    EXPECT_TRUE(shortestPath(2, edges, 0, 1, {false}, {false, true}).nodes.empty());
    EXPECT_TRUE(shortestPath(2, edges, 0, 1, {true}, {false, false}).nodes.empty());
}
