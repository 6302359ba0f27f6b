// Kernel ridge regression of the afraid level at map scale (issue: efficient
// enough for a 2000 x 2000 map, no dense n x n inverse): samples every 25 cm
// along 2 km of robot paths (8000 samples) on a 100 x 100 m map of 5 cm
// cells; sparse fit + evaluation on all 4 million cells.
#include <risknav/afraid/kernel_regression.h>
#include <risknav/localization/CRawlogReader.h>

#include <benchmark/benchmark.h>

#include <random>

using namespace risknav::afraid;

namespace {
std::vector<TKrrSample> samples() {
    std::vector<TKrrSample> s;
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0, 1);
    for (int lane = 0; lane < 20; lane++)  // 20 corridors of 100 m, 5 m apart
        for (double x = 0.125; x < 100; x += 0.25)
            s.push_back({x, 2.5 + 5.0 * lane, u(rng) < 0.02 ? 4.0 * u(rng) : 0.0});
    return s;
}

void BM_KrrFit_8000Samples(benchmark::State& st) {
    const auto s = samples();
    const TKrrOptions o;
    for (auto _ : st)
        benchmark::DoNotOptimize(krrFit(s, o));
    st.counters["samples"] = double(s.size());
}
BENCHMARK(BM_KrrFit_8000Samples)->Unit(benchmark::kMillisecond);

void BM_KrrPredict_2000x2000(benchmark::State& st) {
    const auto s = samples();
    const TKrrOptions o;
    const auto a = krrFit(s, o);
    for (auto _ : st)
        benchmark::DoNotOptimize(krrPredictGrid(s, a, o, 0, 0, 0.05, 2000, 2000));
}
BENCHMARK(BM_KrrPredict_2000x2000)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();

// The rawlog reader on the corridor dataset (2.3 MB, 3959 frames): opening it
// = the size pass + the probe's full MRPT pass in a child (hostile input), then the
// whole read; the difference is what hostile-input safety costs.
const std::string kCorridor =
    std::string(RISKNAV_SOURCE_DIR) + "/datasets/corridor-doors/corridor.rawlog";

void BM_RawlogOpen_Corridor(benchmark::State& st) {
    for (auto _ : st) {
        risknav::localization::CRawlogReader r(kCorridor);
        benchmark::DoNotOptimize(&r);
    }
}
BENCHMARK(BM_RawlogOpen_Corridor)->Unit(benchmark::kMillisecond);

void BM_RawlogReadAll_Corridor(benchmark::State& st) {
    for (auto _ : st) {
        risknav::localization::CRawlogReader r(kCorridor);
        size_t n = 0;
        while (r.next())
            n++;
        st.counters["frames"] = double(n);
    }
}
BENCHMARK(BM_RawlogReadAll_Corridor)->Unit(benchmark::kMillisecond);
