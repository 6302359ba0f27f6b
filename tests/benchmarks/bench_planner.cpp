// The global planner on Nav2's warehouse map (datasets/maps/warehouse: 1006 x
// 1674 cells of 3 cm): setting up the map once (clearance and cost grids),
// and one plan across it, between the two cells with 0.5 m of clearance
// farthest apart along the map's diagonal (what a new goal or a replan
// costs at most there). Counters: length_m, expanded (cells the A* closed),
// cells. Wall time and the thread's CPU time are the same here (one thread).
#include <risknav/common/grid_io.h>
#include <risknav/mapping/TObstacleRule.h>
#include <risknav/planning/CGlobalPlanner.h>

#include <benchmark/benchmark.h>

#include <string>

using namespace risknav;

namespace {
const std::string kSource = RISKNAV_SOURCE_DIR;

struct TWarehouse {
    mrpt::maps::COccupancyGridMap2D grid;
    planning::CGlobalPlanner planner;
    mrpt::math::TPoint2D a, b;
    TWarehouse() {
        common::TMapSourceOptions src;
        src.map_file = kSource + "/datasets/maps/warehouse/warehouse.yaml";
        grid = common::loadOccupancyGrid(src);
        planner.setMap(grid, mapping::TObstacleRule{}, 0.25 + 0.1);
        // the extreme free cells along x + y with 0.5 m of clearance
        const auto& f = planner.field();
        double lo = 1e300, hi = -1e300;
        for (int cy = 0; cy < f.sizeY(); cy++)
            for (int cx = 0; cx < f.sizeX(); cx++) {
                if (f.clearance(cx, cy) < 0.5)
                    continue;
                const double x = f.idx2x(cx), y = f.idx2y(cy);
                if (x + y < lo)
                    lo = x + y, a = {x, y};
                if (x + y > hi)
                    hi = x + y, b = {x, y};
            }
    }
};
TWarehouse& warehouse() {
    static TWarehouse w;
    return w;
}

void BM_GlobalPlan_WarehouseSetMap(benchmark::State& state) {
    auto& w = warehouse();
    for (auto _ : state) {
        planning::CGlobalPlanner p;
        p.setMap(w.grid, mapping::TObstacleRule{}, 0.35);
        benchmark::DoNotOptimize(p.hasMap());
    }
    state.counters["cells"] = double(w.grid.getSizeX()) * w.grid.getSizeY();
}
BENCHMARK(BM_GlobalPlan_WarehouseSetMap)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GlobalPlan_WarehouseAcross(benchmark::State& state) {
    auto& w = warehouse();
    planning::TGlobalPlan plan;
    for (auto _ : state)
        plan = w.planner.plan(w.a, w.b);
    if (!plan.found)
        state.SkipWithError(("no plan: " + plan.reason).c_str());
    state.counters["length_m"] = plan.length;
    state.counters["expanded"] = double(plan.expanded);
    state.counters["cells"] = double(w.grid.getSizeX()) * w.grid.getSizeY();
}
BENCHMARK(BM_GlobalPlan_WarehouseAcross)->Unit(benchmark::kMillisecond)->UseRealTime();
}  // namespace

BENCHMARK_MAIN();
