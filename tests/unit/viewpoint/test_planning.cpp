// Path and viewpoint planning (Yamashita et al. 004 section IV): the segment
// index against brute force, the visibility graph against the full graph,
// clearance of every path, Yen's routes, the greedy viewpoint rule, the world
// reader and grid tracing.
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/geometry/polyline.h>
#include <risknav/viewpoint/CViewpointPlanner.h>
#include <risknav/viewpoint/CVisibilityGraph.h>
#include <risknav/viewpoint/TPolygonWorld.h>
#include <risknav/viewpoint/viewpoint_greedy.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <limits>
#include <queue>
#include <random>

using namespace risknav::viewpoint;
using mrpt::math::TPoint2D;
using risknav::geometry::CSegmentIndex;
using risknav::geometry::TSegment;

namespace {
double bruteDistance(const std::vector<TSegment>& segs, const TPoint2D& p) {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& s : segs)
        d = std::min(d, risknav::geometry::pointSegmentDistance(p, s.a, s.b));
    return d;
}

TPolygonWorld box(double x0, double y0, double x1, double y1, TPolygonWorld w) {
    w.obstacles.push_back({{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}});
    return w;
}

TPolygonWorld emptyRoom(double W, double H) {
    TPolygonWorld w;
    w.xMax = W;
    w.yMax = H;
    return w;
}

// Random axis-aligned boxes that keep off the start (1, H/2) and goal (W-1, H/2).
TPolygonWorld randomWorld(uint64_t seed, int boxes) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> x(2, 8), y(0.5, 5.5), s(0.3, 1.2);
    TPolygonWorld w = emptyRoom(10, 6);
    for (int i = 0; i < boxes; i++) {
        const double cx = x(rng), cy = y(rng), hx = s(rng) / 2, hy = s(rng) / 2;
        w = box(cx - hx, cy - hy, cx + hx, cy + hy, w);
    }
    return w;
}

// Dijkstra on a dense adjacency matrix (the reference).
double denseShortest(const std::vector<std::vector<double>>& W, size_t s, size_t t) {
    const size_t n = W.size();
    std::vector<double> d(n, std::numeric_limits<double>::infinity());
    std::vector<bool> done(n, false);
    d[s] = 0;
    for (size_t it = 0; it < n; it++) {
        size_t u = n;
        for (size_t v = 0; v < n; v++)
            if (!done[v] && (u == n || d[v] < d[u]))
                u = v;
        if (u == n || !std::isfinite(d[u]))
            break;
        done[u] = true;
        for (size_t v = 0; v < n; v++)
            if (std::isfinite(W[u][v]))
                d[v] = std::min(d[v], d[u] + W[u][v]);
    }
    return d[t];
}
}  // namespace

TEST(SegmentIndex, MatchesBruteForce) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 10), dl(-1, 1), dq(0, 1.5);
    std::vector<TSegment> segs;
    for (int i = 0; i < 150; i++) {
        const TPoint2D a{u(rng), u(rng)};
        segs.push_back({a, {a.x + dl(rng), a.y + dl(rng)}});
    }
    segs.push_back({{0, 0}, {10, 0}});  // one long segment across many cells
    const CSegmentIndex idx(segs, 0.7);
    for (int i = 0; i < 2000; i++) {
        const TPoint2D p{u(rng) * 1.4 - 2, u(rng) * 1.4 - 2};  // also outside the grid
        EXPECT_NEAR(idx.distance(p, std::numeric_limits<double>::infinity()),
                    bruteDistance(segs, p), 1e-12);
        EXPECT_NEAR(idx.distance(p, 0.3), std::min(0.3, bruteDistance(segs, p)), 1e-12);
    }
    int hits = 0, misses = 0;
    for (int i = 0; i < 3000; i++) {
        const TPoint2D a{u(rng), u(rng)};
        const TPoint2D b{a.x + 3 * dl(rng), a.y + 3 * dl(rng)};
        const double d = i % 5 == 0 ? 0.0 : dq(rng) * 0.3;
        bool brute = false;
        for (const auto& s : segs) {
            const double dd = risknav::geometry::segmentSegmentDistance(a, b, s.a, s.b);
            brute = brute || (d > 0 ? dd < d : dd == 0);
        }
        EXPECT_EQ(idx.anyWithin(a, b, d), brute) << i;
        (brute ? hits : misses)++;
    }
    EXPECT_GT(hits, 300);
    EXPECT_GT(misses, 300);
}

TEST(VisibilityGraph, ShortestPathEqualsTheFullVisibilityGraph) {
    // The reduced (bitangent, directed) graph loses no shortest path: compare
    // with the full visibility graph of the same nodes, every free pair
    // connected, freedom tested against every world edge without the index.
    const double R = 0.3;
    int compared = 0;
    for (uint64_t seed = 1; seed <= 12; seed++) {
        const TPolygonWorld w = randomWorld(seed, 6);
        const auto segs = w.edges();
        const CSegmentIndex idx(segs, 0.5);
        for (double S : {0.02, 0.1}) {
            const double d = R + S;
            const CVisibilityGraph g(w, idx, d, 16, {1, 3}, {9, 3});
            if (!g.startFree() || !g.goalFree())
                continue;
            const auto& nodes = g.nodes();
            const size_t n = nodes.size();
            std::vector<std::vector<double>> W(n, std::vector<double>(n, INFINITY));
            for (size_t i = 0; i < n; i++)
                for (size_t j = i + 1; j < n; j++) {
                    bool free = true;
                    for (const auto& s : segs)
                        free = free && risknav::geometry::segmentSegmentDistance(
                                           nodes[i].p, nodes[j].p, s.a, s.b) >= d - 1e-9;
                    if (free)
                        W[i][j] = W[j][i] = std::hypot(nodes[i].p.x - nodes[j].p.x,
                                                       nodes[i].p.y - nodes[j].p.y);
                }
            const double ref = denseShortest(W, g.startNode(), g.goalNode());
            const auto paths = g.kShortestPaths(1);
            if (!std::isfinite(ref)) {
                EXPECT_TRUE(paths.empty());
                continue;
            }
            ASSERT_EQ(paths.size(), 1u);
            EXPECT_NEAR(risknav::geometry::polylineLength(paths[0]), ref, 1e-9)
                << "seed " << seed << " S " << S;
            compared++;
        }
    }
    EXPECT_GT(compared, 15);
}

TEST(VisibilityGraph, EveryPathPointKeepsTheSafetyDistance) {
    const double R = 0.3;
    size_t samples = 0;
    for (uint64_t seed = 20; seed < 30; seed++) {
        const TPolygonWorld w = randomWorld(seed, 8);
        const auto segs = w.edges();
        const CSegmentIndex idx(segs, 0.5);
        for (double S : {0.01, 0.05, 0.2}) {
            const CVisibilityGraph g(w, idx, R + S, 8, {1, 3}, {9, 3});
            for (const auto& n : g.nodes()) {
                if (n.corner) {
                    EXPECT_GE(bruteDistance(segs, n.p), R + S - 1e-9);
                }
            }
            for (const auto& path : g.kShortestPaths(5))
                for (size_t i = 0; i + 1 < path.size(); i++)
                    for (int k = 0; k <= 200; k++) {
                        const double f = k / 200.0;
                        const TPoint2D p{path[i].x + f * (path[i + 1].x - path[i].x),
                                         path[i].y + f * (path[i + 1].y - path[i].y)};
                        EXPECT_GE(bruteDistance(segs, p), R + S - 1e-9);
                        EXPECT_FALSE(w.insideObstacle(p));
                        samples++;
                    }
        }
    }
    EXPECT_GT(samples, 20000u);
}

TEST(VisibilityGraph, OneBoxHasExactlyTheTwoTautRoutes) {
    // Round a single box there are two taut routes, over and under, equally
    // long by symmetry; the directed tangent graph gives exactly those (the
    // plain visibility graph's next simple paths double back on themselves).
    const TPolygonWorld w = box(4, 2, 6, 4, emptyRoom(10, 6));
    const CSegmentIndex idx(w.edges(), 0.5);
    const double d = 0.35;
    const CVisibilityGraph g(w, idx, d, 16, {1, 3}, {9, 3});
    const auto paths = g.kShortestPaths(5);
    ASSERT_EQ(paths.size(), 2u);
    const double L0 = risknav::geometry::polylineLength(paths[0]);
    const double L1 = risknav::geometry::polylineLength(paths[1]);
    EXPECT_NEAR(L0, L1, 1e-9);
    // Length of the exact rounded route: tangents to the corner circles
    // (radius d) plus the straight top: a little more than with sharp corners.
    const double sharp = 2 * std::hypot(3.0, 1.0 + d) + 2.0;
    EXPECT_GT(L0, sharp - 0.05);
    EXPECT_LT(L0, sharp + 0.05);
    // One goes over (y > 3), the other under.
    double maxY0 = 0, maxY1 = 0;
    for (const auto& p : paths[0])
        maxY0 = std::max(maxY0, p.y);
    for (const auto& p : paths[1])
        maxY1 = std::max(maxY1, p.y);
    EXPECT_NE(maxY0 > 3, maxY1 > 3);
}

TEST(VisibilityGraph, KShortestAreSortedDistinctAndTaut) {
    for (uint64_t seed = 40; seed < 46; seed++) {
        const TPolygonWorld w = randomWorld(seed, 6);
        const CSegmentIndex idx(w.edges(), 0.5);
        const CVisibilityGraph g(w, idx, 0.35, 16, {1, 3}, {9, 3});
        const auto paths = g.kShortestPaths(10);
        for (size_t i = 1; i < paths.size(); i++) {
            EXPECT_LE(risknav::geometry::polylineLength(paths[i - 1]),
                      risknav::geometry::polylineLength(paths[i]) + 1e-9);
            EXPECT_NE(paths[i - 1], paths[i]);
        }
        for (const auto& p : paths)
            for (size_t i = 1; i + 1 < p.size(); i++) {
                // Taut: the path turns at every vertex, never reverses.
                const double cross = (p[i].x - p[i - 1].x) * (p[i + 1].y - p[i].y) -
                                     (p[i].y - p[i - 1].y) * (p[i + 1].x - p[i].x);
                const double dot = (p[i].x - p[i - 1].x) * (p[i + 1].x - p[i].x) +
                                   (p[i].y - p[i - 1].y) * (p[i + 1].y - p[i].y);
                EXPECT_TRUE(dot > 0 || std::abs(cross) > 1e-12) << "seed " << seed;
            }
    }
}

TEST(Greedy, ConstantErrorsGiveEvenlySpacedViewpoints) {
    // Allowed error A everywhere, every sample observes with the same
    // (ePos, dPhi): m_max = (A - ePos) / k with k = dr + 2 sin(dPhi / 2);
    // eq. (3) then always picks the farthest candidate.
    std::vector<TPathSample> s;
    for (int i = 0; i <= 1000; i++)
        s.push_back({i * 0.01, i * 0.01, 0, 0, 0.05});
    const double ePos = 0.01, dPhi = 0.004, dr = 0.1;
    const double k = dr + 2 * std::sin(dPhi / 2);
    auto reach = [&](size_t i) { return reachFrom(s, i, ePos, dPhi, dr); };
    const size_t exhaustiveEvaluations =
        planViewpointsGreedy(s, 0, 0, dr, reach, false).evaluations;
    for (const bool prune : {true, false}) {
        const auto g = planViewpointsGreedy(s, 0, 0, dr, reach, prune);
        ASSERT_TRUE(g.feasible);
        const double first = 0.05 / dr, step = (0.05 - ePos) / k;
        const size_t expect = size_t(std::ceil((10.0 - first) / step));
        EXPECT_NEAR(double(g.viewpoints.size()), double(expect), 1.0);
        for (size_t v = 1; v < g.viewpoints.size(); v++)
            EXPECT_NEAR(s[g.viewpoints[v]].s - s[g.viewpoints[v - 1]].s, step, 0.011);
        if (prune) {
            EXPECT_LT(g.evaluations, exhaustiveEvaluations / 2);
        }
    }
}

TEST(Greedy, PruningChoosesWhatExhaustiveSearchChooses) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> A(0.02, 0.2), e(0, 0.03), ph(0, 0.02);
    std::bernoulli_distribution blind(0.2);
    int feasible = 0, infeasible = 0;
    for (int t = 0; t < 60; t++) {
        std::vector<TPathSample> s;
        for (int i = 0; i <= 300; i++)
            s.push_back({i * 0.02, 0, 0, 0, A(rng)});
        std::vector<double> ep(s.size()), dp(s.size());
        std::vector<bool> none(s.size());
        for (size_t i = 0; i < s.size(); i++) {
            ep[i] = e(rng);
            dp[i] = ph(rng);
            none[i] = blind(rng);
        }
        auto reach = [&](size_t i) {
            return none[i] ? -1.0 : reachFrom(s, i, ep[i], dp[i], 0.12);
        };
        const auto a = planViewpointsGreedy(s, 0.0, 0.0, 0.12, reach, true);
        const auto b = planViewpointsGreedy(s, 0.0, 0.0, 0.12, reach, false);
        EXPECT_EQ(a.feasible, b.feasible);
        EXPECT_EQ(a.viewpoints, b.viewpoints);
        EXPECT_NEAR(a.reach, b.reach, 1e-12);
        EXPECT_LE(a.evaluations, b.evaluations);
        (a.feasible ? feasible : infeasible)++;
    }
    EXPECT_GT(feasible, 5);
    EXPECT_GT(infeasible, 5);
}

TEST(Greedy, StraightCorridorWithEvenlySpacedLandmarks) {
    // A 12 m corridor 1 m wide (allowed error 0.2 m on its centre line),
    // landmarks every metre on both walls: the real strategies give
    // viewpoints at a nearly constant spacing.
    TPolygonWorld w = emptyRoom(14, 1.0);
    for (int i = 1; i < 14; i++) {
        w.landmarks.push_back({"S" + std::to_string(i), double(i), 0, M_PI / 2, 0.05});
        w.landmarks.push_back(
            {"N" + std::to_string(i), double(i) + 0.5, 1.0, -M_PI / 2, 0.05});
    }
    CViewpointPlanner p;
    p.robot.radius = 0.3;
    p.options.start = {1, 0.5};
    p.options.goal = {13, 0.5};
    p.options.dead_reckoning = 0.1;
    p.setWorld(w);
    const TPlanRow row = p.planPath({{1, 0.5}, {13, 0.5}}, 0.05);
    ASSERT_TRUE(row.feasible);
    ASSERT_GE(row.viewpoints.size(), 6u);
    std::vector<double> gaps;
    for (size_t v = 1; v < row.viewpoints.size(); v++)
        gaps.push_back(row.viewpoints[v].at.s - row.viewpoints[v - 1].at.s);
    std::sort(gaps.begin(), gaps.end());
    const double med = gaps[gaps.size() / 2];
    // At most A / dr = 0.2 / 0.1 = 2 m (an error-free observation), less by
    // the observation's own error.
    EXPECT_GT(med, 1.0);
    EXPECT_LE(med, 2.0 + 1e-9);
    EXPECT_GT(gaps.front(), 0.6 * med);
    EXPECT_LT(gaps.back(), 1.4 * med);
    // Halving the allowed error (a narrower corridor) needs more viewpoints.
    TPolygonWorld narrow = emptyRoom(14, 0.8);
    narrow.landmarks = w.landmarks;
    for (auto& l : narrow.landmarks)
        if (l.y > 0.5)
            l.y = 0.8;
    CViewpointPlanner q = p;
    q.options.start.y = q.options.goal.y = 0.4;
    q.setWorld(narrow);
    const TPlanRow rn = q.planPath({{1, 0.4}, {13, 0.4}}, 0.05);
    EXPECT_TRUE(!rn.feasible || rn.viewpoints.size() > row.viewpoints.size());
}

TEST(Ranking, ShortestFirstThenFewestViewpointsWithoutChaining) {
    // 004 section II, with a length tolerance measured from the shortest
    // plan: 28 mm steps must not chain into a plan 85 mm longer.
    std::vector<TPlanRow> rows(5);
    const double len[5] = {5.523, 5.551, 5.579, 5.608, 5.0};
    const size_t vps[5] = {30, 19, 15, 13, 1};
    for (int i = 0; i < 5; i++) {
        rows[size_t(i)].length = len[i];
        rows[size_t(i)].viewpoints.resize(vps[i]);
        rows[size_t(i)].feasible = i < 4;  // the shortest is infeasible
        rows[size_t(i)].S = 0.04 + 0.01 * i;
    }
    std::vector<const TPlanRow*> all;
    for (const auto& r : rows)
        all.push_back(&r);
    EXPECT_EQ(bestPlan(all, 0.001), &rows[0]);
    EXPECT_EQ(bestPlan(all, 0.03), &rows[1]);
    EXPECT_EQ(bestPlan(all, 0.06), &rows[2]);
    EXPECT_EQ(bestPlan(all, 1.0), &rows[3]);
    // Equal lengths and viewpoints: the larger S.
    rows[1].length = rows[0].length;
    rows[1].viewpoints.resize(30);
    EXPECT_EQ(bestPlan(all, 0.0), &rows[1]);
    for (auto& r : rows)
        r.feasible = false;
    EXPECT_EQ(bestPlan(all, 1.0), nullptr);
}

TEST(World, RingSimplicityMatchesBruteForce) {
    // The bucketed test against every pair of non-adjacent edges.
    auto brute = [](const std::vector<TPoint2D>& r) {
        const size_t n = r.size();
        for (size_t i = 0; i < n; i++) {
            const auto &a = r[i], &b = r[(i + 1) % n], &c = r[(i + 2) % n];
            if (a.x == b.x && a.y == b.y)
                return false;
            if (risknav::geometry::orient(a, b, c) == 0 &&
                (c.x - b.x) * (a.x - b.x) + (c.y - b.y) * (a.y - b.y) > 0)
                return false;
            for (size_t j = i + 2; j < n; j++) {
                if (i == 0 && j == n - 1)
                    continue;
                if (risknav::geometry::segmentsIntersect(a, b, r[j], r[(j + 1) % n]))
                    return false;
            }
        }
        return true;
    };
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(0, 1);
    std::uniform_int_distribution<int> grid(0, 6);
    int simple = 0, notSimple = 0;
    for (int t = 0; t < 3000; t++) {
        const size_t n = 3 + size_t(t % 9);
        std::vector<TPoint2D> r;
        if (t % 3 == 0) {
            // Star-shaped (simple unless points coincide) with jitter.
            for (size_t i = 0; i < n; i++) {
                const double a = 2 * M_PI * (double(i) + 0.3 * u(rng)) / double(n);
                const double rad = 0.5 + u(rng);
                r.push_back({rad * std::cos(a), rad * std::sin(a)});
            }
        } else
            for (size_t i = 0; i < n; i++)  // on a coarse lattice: collinear cases
                r.push_back({double(grid(rng)), double(grid(rng))});
        const bool b = brute(r);
        EXPECT_EQ(risknav::geometry::ringIsSimple(r), b) << "case " << t;
        (b ? simple : notSimple)++;
    }
    EXPECT_GT(simple, 500);
    EXPECT_GT(notSimple, 500);
    // A 10000-vertex circle (the per-polygon limit) is simple, and one more
    // vertex than the limit is refused by the reader.
    std::string line = "bounds 0 0 100 100\nobstacle";
    std::vector<TPoint2D> circle;
    for (int i = 0; i < 10000; i++) {
        const double a = 2 * M_PI * i / 10000;
        circle.push_back({50 + 40 * std::cos(a), 50 + 40 * std::sin(a)});
        line +=
            " " + std::to_string(circle.back().x) + " " + std::to_string(circle.back().y);
    }
    EXPECT_TRUE(risknav::geometry::ringIsSimple(circle));
    EXPECT_NO_THROW(parsePolygonWorld(line + "\n", "w.txt"));
    EXPECT_THROW(parsePolygonWorld(line + " 50 50.5\n", "w.txt"),
                 risknav::common::CBadInputError);
}

TEST(World, ReaderAcceptsTheFormatAndOrientsRings) {
    const auto w = parsePolygonWorld(
        "# comment\nbounds 0 0 10 5\nobstacle 1 1 1 2 2 2 2 1  # clockwise\n"
        "obstacle 4 1 8 1 8 4 4 4\nhole 5 2 5 3 7 3 7 2\nlandmark A 4 2.5 180 0.08\n"
        "landmark B 0 1 0\n",
        "w.txt");
    ASSERT_EQ(w.obstacles.size(), 2u);
    EXPECT_GT(risknav::geometry::signedArea(w.obstacles[0].outer), 0);
    EXPECT_LT(risknav::geometry::signedArea(w.obstacles[1].holes[0]), 0);
    EXPECT_TRUE(w.insideObstacle({1.5, 1.5}));
    EXPECT_TRUE(w.insideObstacle({4.5, 1.5}));
    EXPECT_FALSE(w.insideObstacle({6, 2.5}));  // in the hole
    EXPECT_TRUE(w.insideObstacle({11, 1}));    // outside the bounds
    EXPECT_DOUBLE_EQ(w.landmarks[0].radius, 0.08);
    EXPECT_NEAR(w.landmarks[0].facing, M_PI, 1e-15);
    EXPECT_NO_THROW(validateWorld(w, "w.txt"));
}

TEST(World, BadTextGivesOneClearError) {
    const std::vector<std::pair<std::string, std::string>> cases{
        {"obstacle 0 0 1 0 1 1\n", "no 'bounds"},
        {"bounds 0 0 1\n", "w.txt:1: bounds: expected"},
        {"bounds 0 0 -1 1\n", "XMAX must be > XMIN"},
        {"bounds 0 0 5 5\nbounds 0 0 5 5\n", "w.txt:2: bounds given twice"},
        {"bounds 0 0 5 5\nobstacle 1 1 2 2\n", "needs >= 3 vertices"},
        {"bounds 0 0 5 5\nobstacle 1 1 2 2 3\n", "odd number"},
        {"bounds 0 0 5 5\nobstacle 1 1 3 3 3 1 1 3\n", "not simple"},
        {"bounds 0 0 5 5\nobstacle 1 1 2 2 3 3\n",
         "not simple"},  // collinear: folds back
        {"bounds 0 0 5 5\nobstacle 1 1 2 1 0x2 2\n", "'0x2' is not a decimal number"},
        {"bounds 0 0 5 5\nobstacle 1 1 2 1 nan 2\n", "not a decimal number"},
        {"bounds 0 0 5 5\nobstacle 1 1 2 1 1e300 2\n", "beyond"},
        {"bounds 0 0 5 5\nhole 1 1 2 1 2 2\n", "no obstacle before it"},
        {"bounds 0 0 5 5\nobstacle 1 1 2 1 2 2 1 2\nhole 0 0 3 0 3 3\n",
         "outside its obstacle"},
        {"bounds 0 0 5 5\nlandmark A 1 1\n", "expected 'landmark ID"},
        {"bounds 0 0 5 5\nlandmark A 1 1 0 -1\n", "RADIUS must be in"},
        {"bounds 0 0 5 5\npolygon 1 1\n", "unknown keyword 'polygon'"},
    };
    for (const auto& [text, expect] : cases) {
        try {
            parsePolygonWorld(text, "w.txt");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const risknav::common::CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find(expect), std::string::npos)
                << e.what() << " (expected: " << expect << ")";
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
    }
}

TEST(World, LandmarkInsideAnObstacleOrFacingItsWallIsRefused) {
    auto check = [](const std::string& text, const std::string& expect) {
        const auto w = parsePolygonWorld(text, "w.txt");
        try {
            validateWorld(w, "w.txt");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const risknav::common::CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
        }
    };
    const std::string base = "bounds 0 0 5 5\nobstacle 1 1 3 1 3 3 1 3\n";
    check(base + "landmark A 2 2 0\n", "'A' lies inside an obstacle");
    check(base + "landmark A 3 2 180\n",
          "faces into its wall");  // on the edge, facing in
    check(base + "landmark A 0 2 180\n",
          "faces into its wall");  // outer wall, facing out
    check(base + "landmark A 3 2 0\nlandmark A 1 2 180\n", "given twice");
    check(base + "landmark A 6 2 0\n", "outside the bounds");
    EXPECT_NO_THROW(
        validateWorld(parsePolygonWorld(base + "landmark A 3 2 0\n", "w"), "w"));
}

TEST(World, GridObstaclesAreTracedWithTheirHoles) {
    // A 4 x 3 m grid at 5 cm: a solid box and a closed room (walls only).
    mrpt::maps::COccupancyGridMap2D g(0, 4, 0, 3, 0.05f);
    g.fill(1.0f);
    auto occ = [&](double x0, double y0, double x1, double y1) {
        for (int cy = g.y2idx(y0); cy <= g.y2idx(y1 - 1e-9); cy++)
            for (int cx = g.x2idx(x0); cx <= g.x2idx(x1 - 1e-9); cx++)
                g.setCell(cx, cy, 0.0f);
    };
    occ(0.5, 0.5, 1.0, 1.2);  // box
    occ(2.0, 0.5, 3.5, 0.6);  // room: four walls
    occ(2.0, 2.4, 3.5, 2.5);
    occ(2.0, 0.5, 2.1, 2.5);
    occ(3.4, 0.5, 3.5, 2.5);
    risknav::mapping::TObstacleRule rule;
    TPolygonWorld w = emptyRoom(4, 3);
    w.obstacles = obstaclesFromGrid(g, rule, 0.02);
    ASSERT_EQ(w.obstacles.size(), 2u);
    size_t holes = 0;
    for (const auto& o : w.obstacles)
        holes += o.holes.size();
    EXPECT_EQ(holes, 1u);
    // Every obstacle cell's centre is inside a traced obstacle; the room's
    // inside (away from the walls) and the open space are free.
    for (int cy = 0; cy < int(g.getSizeY()); cy++)
        for (int cx = 0; cx < int(g.getSizeX()); cx++)
            if (g.getCell(cx, cy) < 0.5f) {
                EXPECT_TRUE(w.insideObstacle({g.idx2x(cx), g.idx2y(cy)}))
                    << cx << "," << cy;
            }
    EXPECT_FALSE(w.insideObstacle({2.75, 1.5}));
    EXPECT_FALSE(w.insideObstacle({1.5, 2.0}));
}

TEST(TCameraOptions, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    // config/risknav-viewpoint-plan.ini documents [Camera] key by key, each
    // with its default
    mrpt::config::CConfigFileMemory doc(risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-viewpoint-plan.ini")));
    const auto keys = TCameraOptions().keys();
    ASSERT_EQ(keys.size(), 10u);
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists("Camera", k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        const std::string v = doc.read_string("Camera", k.key, "");
        EXPECT_EQ(risknav::common::trim(v.substr(0, v.find("//"))), k.defaultText)
            << k.key;
    }
}

TEST(TViewpointPlanOptions, TheDocumentedConfigHoldsEveryDeclaredKey) {
    // config/risknav-viewpoint-plan.ini documents [ViewpointPlan] key by key;
    // the optional map's keys (read only with map_file) are there commented
    // out, as "; key = value"
    const std::string text = risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-viewpoint-plan.ini"));
    mrpt::config::CConfigFileMemory doc(text);
    const auto keys = risknav::viewpoint::TViewpointPlanOptions().keys();
    ASSERT_EQ(keys.size(), 25u);  // the map's keys listed although no map is set
    for (const auto& k : keys) {
        EXPECT_FALSE(k.doc.empty()) << k.key;
        const bool given = doc.keyExists("ViewpointPlan", k.key);
        const bool commented = text.find("\n;" + k.key + " ") != std::string::npos;
        EXPECT_TRUE(given || commented) << k.key;
    }
}
