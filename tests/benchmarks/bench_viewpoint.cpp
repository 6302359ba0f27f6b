// Path and viewpoint planner (M4, Yamashita et al.) speed. Issue's target:
// the full sweep (9 values of S, k = 10 paths each, viewpoint planning for
// all) on a map with 50 obstacles and 30 landmarks in <= 500 ms on this
// machine (2 cores).
//
// The world is built in code from a seeded generator (deterministic: its own
// uniform draws from mt19937_64, no implementation-defined distributions): a
// 20 x 14 m room, 50 convex obstacles (axis-aligned boxes, rotated
// rectangles, regular pentagons, 0.3-1.2 m across) at least kGap apart from
// each other and from the walls, and 30 landmarks (radius 5 cm) centred
// exactly on obstacle or wall edges, each facing the edge's outward normal,
// 24 of them within 2.5 m of the room's centre line. Start and goal sit at
// the room's two short ends, on that line. The planner: robot radius 0.3 m,
// S = 20 ... 100 mm, k = 10, 10 % dead reckoning, camera range 5 m, the other
// settings the defaults.
//
// Set RISKNAV_BENCH_WORLD_OUT=FILE to also write the world in the polygon
// world text format (for risknav-viewpoint-plan and its picture).
#include <risknav/geometry/CSegmentIndex.h>
#include <risknav/geometry/segments.h>
#include <risknav/viewpoint/CViewpointPlanner.h>
#include <risknav/viewpoint/CVisibilityGraph.h>
#include <risknav/viewpoint/TPolygonWorld.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace risknav;
using namespace risknav::viewpoint;
using mrpt::math::TPoint2D;

namespace {
constexpr double kW = 20, kH = 14;  // [m] room
constexpr int kObstacles = 50, kLandmarks = 30;
constexpr int kNearRoute = 24;    // landmarks within kBand of the centre line
constexpr double kBand = 2.5;     // [m]
constexpr double kGap = 1.0;      // [m] obstacle-obstacle and obstacle-wall clearance
constexpr double kEndFree = 1.6;  // [m] obstacle-free radius around start and goal
const TPoint2D kStart{0.8, kH / 2}, kGoal{kW - 0.8, kH / 2};

using TRing = std::vector<TPoint2D>;

/** Uniform in [a, b) from the top 53 bits: the same numbers everywhere. */
struct TRng {
    std::mt19937_64 g;
    explicit TRng(uint64_t seed) : g(seed) {}
    double u(double a = 0, double b = 1) {
        return a + (b - a) * double(g() >> 11) * 0x1.0p-53;
    }
    size_t pick(size_t n) { return size_t(u() * double(n)) % n; }
};

// A convex obstacle, counter-clockwise (the obstacle on the left), centred at c.
TRing randomShape(TRng& r, const TPoint2D& c) {
    TRing ring;
    const int kind = int(r.pick(3));
    if (kind == 2) {  // regular pentagon, 0.3-1.2 m across (2 x circumradius)
        const double rho = r.u(0.15, 0.6), a0 = r.u(0, 2 * M_PI);
        for (int i = 0; i < 5; i++) {
            const double a = a0 + 2 * M_PI * i / 5;
            ring.push_back({c.x + rho * std::cos(a), c.y + rho * std::sin(a)});
        }
        return ring;
    }
    const double w = r.u(0.3, 1.2), h = r.u(0.3, 1.2);
    const double th = kind == 0 ? 0.0 : r.u(0, M_PI);
    const double ct = std::cos(th), st = std::sin(th);
    for (const auto& [sx, sy] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        const double lx = sx * w / 2, ly = sy * h / 2;
        ring.push_back({c.x + ct * lx - st * ly, c.y + st * lx + ct * ly});
    }
    return ring;
}

double ringDistance(const TRing& a, const TRing& b) {
    double d = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < a.size(); i++)
        for (size_t j = 0; j < b.size(); j++)
            d = std::min(
                d, geometry::segmentSegmentDistance(a[i], a[(i + 1) % a.size()], b[j],
                                                    b[(j + 1) % b.size()]));
    return d;
}

TPolygonWorld makeWorld(uint64_t seed) {
    TRng r(seed);
    TPolygonWorld w;
    w.xMin = 0, w.yMin = 0, w.xMax = kW, w.yMax = kH;
    // Obstacles: random sequential placement with exact edge-to-edge clearances.
    for (int attempt = 0; int(w.obstacles.size()) < kObstacles; attempt++) {
        if (attempt > 200000)
            throw std::runtime_error("bench_viewpoint: cannot place 50 obstacles");
        const TPoint2D c{r.u(kGap, kW - kGap), r.u(kGap, kH - kGap)};
        const TRing ring = randomShape(r, c);
        bool ok = true;
        for (const auto& p : ring)
            ok = ok && p.x >= kGap && p.x <= kW - kGap && p.y >= kGap && p.y <= kH - kGap;
        for (const TPoint2D& e : {kStart, kGoal}) {
            double d = std::numeric_limits<double>::infinity();
            for (size_t i = 0; i < ring.size(); i++)
                d = std::min(d, geometry::pointSegmentDistance(
                                    e, ring[i], ring[(i + 1) % ring.size()]));
            ok = ok && d >= kEndFree;
        }
        for (size_t i = 0; ok && i < w.obstacles.size(); i++)
            ok = ringDistance(ring, w.obstacles[i].outer) >= kGap;
        if (ok)
            w.obstacles.push_back({ring, {}});
    }
    // Landmarks: on an edge, centred exactly on it with its whole width (2
    // radii) and 5 cm either side inside the edge, facing the edge's outward
    // normal (the right of an obstacle-on-the-left edge), at least 0.4 m from
    // every other landmark. The first kNearRoute ones lie within kBand of the
    // room's centre line (the start-goal line, where the short routes run)
    // and do not face away from it; the others anywhere (a wall for about a
    // quarter of them, else an obstacle's edge).
    const auto edges = w.edges();  // the obstacles' rings, then the 4 walls
    const size_t obstacleEdges = edges.size() - 4;
    for (int attempt = 0; int(w.landmarks.size()) < kLandmarks; attempt++) {
        if (attempt > 200000)
            throw std::runtime_error("bench_viewpoint: cannot place 30 landmarks");
        const bool nearRoute = int(w.landmarks.size()) < kNearRoute;
        const auto& e = !nearRoute && r.u() < 0.25 ? edges[obstacleEdges + r.pick(4)]
                                                   : edges[r.pick(edges.size())];
        const double dx = e.b.x - e.a.x, dy = e.b.y - e.a.y, L = std::hypot(dx, dy);
        TLandmark l;
        l.radius = 0.05;
        const double margin = l.radius + 0.05;
        if (L < 2 * margin + 0.1)
            continue;
        const double t = r.u(margin, L - margin) / L;
        l.x = e.a.x + t * dx;
        l.y = e.a.y + t * dy;
        const double off = std::abs(l.y - kH / 2);
        const double offFront = std::abs(l.y - dx / L - kH / 2);  // 1 m in front
        if (nearRoute && (off > kBand || offFront > off + 0.3))
            continue;
        l.facing = std::atan2(-dx, dy);  // right normal (dy, -dx)
        bool ok = true;
        for (const auto& o : w.landmarks)
            ok = ok && std::hypot(o.x - l.x, o.y - l.y) >= 0.4;
        if (!ok)
            continue;
        l.id = "L" + std::to_string(w.landmarks.size() + 1);
        w.landmarks.push_back(l);
    }
    return w;
}

std::string worldText(const TPolygonWorld& w) {
    std::string s = "# bench_viewpoint's generated world\n";
    char buf[128];
    std::snprintf(buf, sizeof buf, "bounds %g %g %g %g\n", w.xMin, w.yMin, w.xMax,
                  w.yMax);
    s += buf;
    for (const auto& o : w.obstacles) {
        s += "obstacle";
        for (const auto& p : o.outer) {
            std::snprintf(buf, sizeof buf, " %.6f %.6f", p.x, p.y);
            s += buf;
        }
        s += "\n";
    }
    for (const auto& l : w.landmarks) {
        std::snprintf(buf, sizeof buf, "landmark %s %.9f %.9f %.9f %g\n", l.id.c_str(),
                      l.x, l.y, l.facing * 180 / M_PI, l.radius);
        s += buf;
    }
    return s;
}

const TPolygonWorld& world() {
    static const TPolygonWorld w = [] {
        TPolygonWorld g = makeWorld(20240611);
        if (const char* out = std::getenv("RISKNAV_BENCH_WORLD_OUT"))
            std::ofstream(out) << worldText(g);
        return g;
    }();
    return w;
}

void setUp(CViewpointPlanner& p, int threads) {
    p.robot.radius = 0.3;
    p.camera.max_range = 5;
    p.options.safety_margins = {0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10};
    p.options.k_paths = 10;
    p.options.dead_reckoning = 0.1;
    p.options.start = kStart;
    p.options.goal = kGoal;
    p.options.threads = threads;
    p.setWorld(world());  // validateWorld(): throws on a bad generated world
}

void fullSweep(benchmark::State& st, int threads) {
    CViewpointPlanner p;
    setUp(p, threads);
    for (auto _ : st)
        p.plan();
    size_t rows = 0, feasible = 0, feasibleS = 0;
    for (const auto& sp : p.sweep()) {
        size_t f = 0;
        for (const auto& row : sp.rows)
            f += row.feasible ? 1 : 0;
        rows += sp.rows.size();
        feasible += f;
        feasibleS += f > 0 ? 1 : 0;
    }
    st.counters["feasible_plans"] = double(feasible);
    st.counters["S_with_feasible"] = double(feasibleS);
    st.counters["total_paths"] = double(rows);
    st.counters["routes"] = double(p.routeCount());
    st.counters["graph_nodes_first_S"] =
        p.sweep().empty() ? 0.0 : double(p.sweep()[0].nodes);
    st.counters["graph_edges_first_S"] =
        p.sweep().empty() ? 0.0 : double(p.sweep()[0].edges);
    st.counters["optimal"] = p.optimal() ? 1.0 : 0.0;
    if (const auto o = p.optimal()) {
        const TPlanRow& row = p.sweep()[o->first].rows[o->second];
        st.counters["optimal_S_mm"] = row.S * 1000;
        st.counters["optimal_length_m"] = row.length;
        st.counters["optimal_viewpoints"] = double(row.viewpoints.size());
    }
}

void BM_ViewpointFullSweep(benchmark::State& st) {
    fullSweep(st, 0);
}
BENCHMARK(BM_ViewpointFullSweep)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ViewpointFullSweep_1Thread(benchmark::State& st) {
    fullSweep(st, 1);
}
BENCHMARK(BM_ViewpointFullSweep_1Thread)->Unit(benchmark::kMillisecond)->UseRealTime();

// One S (50 mm) of the sweep without the viewpoints: the grown C-obstacles'
// visibility graph alone, and with Yen's 10 shortest paths on it.
const geometry::CSegmentIndex& edgeIndex() {
    static const geometry::CSegmentIndex index(world().edges(), 0.5);
    return index;
}

void BM_VisibilityGraph_OneS(benchmark::State& st) {
    size_t nodes = 0, edges = 0;
    for (auto _ : st) {
        const CVisibilityGraph g(world(), edgeIndex(), 0.3 + 0.05, 16, kStart, kGoal);
        nodes = g.nodes().size();
        edges = g.edges().size();
    }
    st.counters["graph_nodes"] = double(nodes);
    st.counters["graph_edges"] = double(edges);
}
BENCHMARK(BM_VisibilityGraph_OneS)->Unit(benchmark::kMillisecond);

void BM_VisibilityGraphAndKShortest_OneS(benchmark::State& st) {
    size_t paths = 0;
    for (auto _ : st) {
        const CVisibilityGraph g(world(), edgeIndex(), 0.3 + 0.05, 16, kStart, kGoal);
        const auto k = g.kShortestPaths(10);
        paths = k.size();
        benchmark::DoNotOptimize(k.data());
    }
    st.counters["paths"] = double(paths);
}
BENCHMARK(BM_VisibilityGraphAndKShortest_OneS)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
