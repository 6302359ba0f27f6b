// Simulation speed of risknav-simulate's engine on the corridor world
// (181-beam laser at 5 Hz, door pedestrians, corridor walkers): the counter
// "realtime_x" is simulated seconds per wall-clock second, all output
// (rawlog, ground truth, events, PNG) included. "peak_rss_MB" is the
// process's peak resident memory so far.
#include <risknav/common/CIniConfig.h>
#include <risknav/common/COutputDir.h>
#include <risknav/sim/CWorldSimulator.h>

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>

namespace fs = std::filesystem;
using namespace risknav;

namespace {
double peakRssMB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss / 1024.0;
}

void BM_SimulateCorridor(benchmark::State& state) {
    const std::string ini =
        std::string(RISKNAV_SOURCE_DIR) + "/datasets/corridor-doors/world.ini";
    const std::string out =
        (fs::temp_directory_path() / ("risknav-bench-" + std::to_string(::getpid())))
            .string();
    double simulated = 0, frames = 0;
    for (auto _ : state) {
        common::CIniConfig cfg(ini);
        cfg.applyOverride("Route.laps=" + std::to_string(state.range(0)));
        sim::CWorldSimulator s;
        s.loadFromConfigFile(cfg, std::nullopt);
        common::COutputDir dir(out);
        const auto j = s.run(dir, true);
        dir.commit();
        simulated += j["duration_s"].get<double>();
        frames += j["frames"].get<double>();
    }
    fs::remove_all(out);
    state.counters["realtime_x"] =
        benchmark::Counter(simulated, benchmark::Counter::kIsRate);
    state.counters["frames_per_s"] =
        benchmark::Counter(frames, benchmark::Counter::kIsRate);
    state.counters["peak_rss_MB"] = peakRssMB();
}
BENCHMARK(BM_SimulateCorridor)
    ->Arg(1)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_LaserScan181(benchmark::State& state) {
    common::TMapSourceOptions m;
    m.map_file =
        std::string(RISKNAV_SOURCE_DIR) + "/datasets/corridor-doors/corridor.png";
    const sim::CRayCastMap map(common::loadOccupancyGrid(m), mapping::TObstacleRule());
    sim::CRangeSensorSim laser;
    std::mt19937_64 rng(1);
    const std::vector<sim::TDisc> people = {{12, 4, 0.25, 1}, {16, 3.5, 0.25, 2}};
    double x = 2;
    for (auto _ : state) {
        benchmark::DoNotOptimize(
            laser.simulate(map, {x, 4.5, 0}, people, mrpt::Clock::now(), rng));
        x = x > 27 ? 2 : x + 0.04;
    }
}
BENCHMARK(BM_LaserScan181)->Unit(benchmark::kMicrosecond);
}  // namespace

BENCHMARK_MAIN();
