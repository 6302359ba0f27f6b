// D_max and whole-route evaluation speed (issue: >= 100x faster than brute
// force for 1,000 poses on a 1000 x 1000 grid with 5 % obstacles, measured
// side by side; a 50 m route at 5 cm steps in <= 50 ms, per error model and
// propagation).
#include <risknav/risk/CObstacleField.h>
#include <risknav/risk/path_risk.h>

#include <benchmark/benchmark.h>

#include <array>
#include <random>
#include <string>

using namespace risknav::risk;
using mrpt::math::TPoint2D;

namespace {
// 1000 x 1000 cells of 5 cm (50 x 50 m), 5 % of them obstacles at random.
const CObstacleField& randomField() {
    static const CObstacleField f = [] {
        mrpt::maps::COccupancyGridMap2D g(0, 50, 0, 50, 0.05f);
        g.fill(1.0f);
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(0, 1);
        for (unsigned y = 0; y < g.getSizeY(); y++)
            for (unsigned x = 0; x < g.getSizeX(); x++)
                if (u(rng) < 0.05)
                    g.setCell(x, y, 0.0f);
        // Radius 0 keeps the 5 %: grown by 0.25 m nearly every cell would be an
        // obstacle.
        return CObstacleField(g, {}, 0.0);
    }();
    return f;
}

// 1000 poses along a 50 m diagonal with covariances propagated along it
// (paper's robot, systematic model): ellipses from millimetres to metres.
struct TPose {
    double x, y;
    Eigen::Matrix2d cov;
};
const std::vector<TPose>& poses() {
    static const std::vector<TPose> p = [] {
        TRiskOptions o;
        o.sigmaP0.diagonal() << 1e-6, 1e-6, 0.01;
        const auto steps =
            motionProfile({{0, 0}, {35.3, 35.3}}, o.odometry, 0.3, 0.5, 0.05);
        auto z = augmentedInitial(o.sigmaP0, o.odometry);
        std::vector<TPose> out;
        const size_t every = steps.size() / 1000;
        for (size_t i = 0; i < steps.size() && out.size() < 1000; i++) {
            z = propagateSystematic(z, steps[i].theta, steps[i].uL, steps[i].uR,
                                    steps[i].tau, o.odometry);
            if (i % every == 0)
                out.push_back({7 + steps[i].x, 7 + steps[i].y, z.block<2, 2>(0, 0)});
        }
        return out;
    }();
    return p;
}

void BM_DmaxFast_1000Poses(benchmark::State& st) {
    const auto& f = randomField();
    for (auto _ : st)
        for (const auto& p : poses())
            benchmark::DoNotOptimize(f.dMax(p.x, p.y, p.cov));
    st.counters["obstacle_cells"] = double(f.obstacleCount());
}
BENCHMARK(BM_DmaxFast_1000Poses)->Unit(benchmark::kMillisecond);

void BM_DmaxBruteForce_1000Poses(benchmark::State& st) {
    const auto& f = randomField();
    for (auto _ : st)
        for (const auto& p : poses())
            benchmark::DoNotOptimize(f.dMaxBruteForce(p.x, p.y, p.cov));
}
BENCHMARK(BM_DmaxBruteForce_1000Poses)->Unit(benchmark::kMillisecond)->Iterations(2);

// A 50 m route (30 m, a 90 deg turn, 20 m) through a 50 x 50 m office-like
// grid with furniture, evaluated at 5 cm steps: pose-error propagation at
// tau = 0.05 s (3400 steps) plus 1000 D_max queries (robot radius 0.25 m,
// exact disc growth). Arguments: error model (0 per_step, 1 systematic) and
// propagation (0 linear, 1 unscented, 2 cubature5 = the default, 3 sampled
// with 1000 draws). Target: <= 50 ms with the default.
void BM_Route50m(benchmark::State& st) {
    static const CObstacleField f = [] {
        mrpt::maps::COccupancyGridMap2D g(0, 50, 0, 50, 0.05f);
        g.fill(1.0f);
        std::mt19937_64 rng(8);
        std::uniform_real_distribution<double> u(0, 1);
        for (int k = 0; k < 300; k++)  // furniture blocks, kept off the route's 3 m band
        {
            const double x = u(rng) * 48, y = u(rng) * 48, w = 0.4 + u(rng) * 1.5,
                         h = 0.4 + u(rng) * 1.5;
            for (double yy = y; yy < y + h; yy += 0.05)
                for (double xx = x; xx < x + w; xx += 0.05) {
                    const bool onRoute =
                        (std::abs(yy - 10) < 1.5 && xx > 8 && xx < 41.5) ||
                        (std::abs(xx - 40) < 1.5 && yy > 8 && yy < 31.5);
                    if (!onRoute)
                        g.setPos(float(xx), float(yy), 0.0f);
                }
        }
        return CObstacleField(g, {}, 0.25);
    }();
    TRiskOptions o;
    o.sigmaP0.diagonal() << 1e-6, 1e-6, 0.01;
    o.evalStep = 0.05;
    o.model = st.range(0) ? TErrorModel::Systematic : TErrorModel::PerStep;
    o.propagation = TPropagation(st.range(1));
    const std::vector<TPoint2D> route = {{10, 10}, {40, 10}, {40, 30}};
    double U = 0;
    size_t samples = 0;
    for (auto _ : st) {
        const auto r = evaluatePathRisk(route, {}, f, o);
        U = r.U;
        samples = r.samples.size();
    }
    st.counters["U"] = U;
    st.counters["samples"] = double(samples);
    st.SetLabel(std::string(st.range(0) ? "systematic" : "per_step") + "/" +
                std::array<const char*, 4>{"linear", "unscented", "cubature5",
                                           "sampled"}[size_t(st.range(1))]);
}
BENCHMARK(BM_Route50m)
    ->ArgsProduct({{0, 1}, {0, 1, 2, 3}})
    ->ArgNames({"systematic", "propagation"})
    ->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
