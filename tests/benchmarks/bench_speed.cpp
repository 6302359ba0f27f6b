// One control cycle of the adaptive speed controller (M1): two
// sensor updates on the robot-centred grids, fusion, the planning field, the
// memory's update and cost on (50 m at 0.25 m, the default) and the decision
// with four A* plans, as risknav-explore runs it. The scans and the map come from the
// office world after the robot has driven into the corridor (a realistic map: walls,
// doors, unknown beyond), on a 200 x 200 grid (10 m, the paper's) and on a
// 400 x 400 one (20 m at 5 cm) to show how the cost grows.
#include <risknav/common/CIniConfig.h>
#include <risknav/mapping/CFreeSpaceMemory.h>
#include <risknav/mapping/free_space.h>
#include <risknav/speed/CExplorer.h>

#include <benchmark/benchmark.h>

using namespace risknav;

namespace {
struct TScene {
    speed::CExplorer ex;
    sim::CSimWorld::TScans scans;
    mrpt::math::TPose2D pose;
    mapping::CLocalProbGrid laser, range2;
};

/** The office, the robot at the corridor's west end looking east, grids of
 * `cells` a side that have seen 10 scans from there. */
TScene& scene(int cells) {
    static std::map<int, std::unique_ptr<TScene>> scenes;
    auto& s = scenes[cells];
    if (s)
        return *s;
    s = std::make_unique<TScene>();
    common::CIniConfig c(std::string(RISKNAV_SOURCE_DIR) +
                         "/datasets/office/explore.ini");
    s->ex.loadFromConfigFile(c, {});
    s->pose = mrpt::math::TPose2D(3.0, 7.0, 0.0);
    s->ex.world.reset(s->pose, 1);
    s->laser = mapping::CLocalProbGrid(cells, 0.05, s->pose.x, s->pose.y);
    s->range2 = s->laser;
    for (int k = 0; k < 10; k++) {
        s->scans = s->ex.world.sense();
        s->laser.integrateScan(s->pose, *s->scans.laser, s->ex.laserModel);
        s->range2.integrateScan(s->pose, *s->scans.range2, s->ex.range2Model);
    }
    return *s;
}

void BM_ControlCycle(benchmark::State& st) {
    auto& s = scene(int(st.range(0)));
    const speed::CAdaptiveSpeedController ctrl(s.ex.speed, s.ex.world.robot.radius,
                                               s.ex.necessaryObservations());
    const double radius = s.ex.world.robot.radius;
    const mrpt::math::TPoint2D goal(15.5, 7.0);  // beyond the local map
    mapping::CFreeSpaceMemory memory(s.ex.explore.memory_size,
                                     s.ex.explore.memory_resolution, 3.0, 7.0);
    for (auto _ : st) {
        // a copy of the grids (each cycle updates the same state); 2 x 160 KB
        // at 200 x 200, a few % of the cycle
        auto laser = s.laser, range2 = s.range2;
        laser.integrateScan(s.pose, *s.scans.laser, s.ex.laserModel);
        range2.integrateScan(s.pose, *s.scans.range2, s.ex.range2Model);
        auto fused = mapping::fuseGrids(laser, range2, 0.7, 0.2);
        speed::markFootprintFree(fused, s.pose, radius);
        const auto field =
            speed::computePlanningField(fused, radius, ctrl.wayOnBand(0.05));
        memory.update(fused);
        bool ready = false;
        speed::TTargetHints hints;
        hints.goalCost = [&](double x, double y) {
            if (!ready) {
                memory.computeCostToGoal(goal, s.ex.speed.frontier_goal_weight, fused,
                                         radius);
                ready = true;
            }
            return memory.costToGoal(x, y, radius + s.ex.speed.margins.back() + 0.15);
        };
        const auto d = ctrl.decide(field, s.pose, goal, -1, hints);
        benchmark::DoNotOptimize(d.speed);
    }
    st.counters["cells"] = double(st.range(0) * st.range(0));
}
BENCHMARK(BM_ControlCycle)
    ->Arg(200)
    ->Arg(400)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_SensorUpdatesOnly(benchmark::State& st) {
    auto& s = scene(int(st.range(0)));
    for (auto _ : st) {
        auto laser = s.laser, range2 = s.range2;
        laser.integrateScan(s.pose, *s.scans.laser, s.ex.laserModel);
        range2.integrateScan(s.pose, *s.scans.range2, s.ex.range2Model);
        benchmark::DoNotOptimize(laser.probabilities().data());
    }
}
BENCHMARK(BM_SensorUpdatesOnly)->Arg(200)->Arg(400)->Unit(benchmark::kMillisecond);
/** One sensor's update alone on the 200 x 200 grid: /0 the laser (181 rays,
 * 180 deg, 10 m), /1 the second sensor (72 rays, 360 deg, 5 m), /2 neither
 * (the grid's copy each iteration makes, to subtract). */
void BM_OneSensorUpdate(benchmark::State& st) {
    auto& s = scene(200);
    for (auto _ : st) {
        auto grid = s.laser;
        if (st.range(0) == 0)
            grid.integrateScan(s.pose, *s.scans.laser, s.ex.laserModel);
        else if (st.range(0) == 1)
            grid.integrateScan(s.pose, *s.scans.range2, s.ex.range2Model);
        benchmark::DoNotOptimize(grid.probabilities().data());
    }
}
BENCHMARK(BM_OneSensorUpdate)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

/** Classification and fusion of the two grids alone. */
void BM_FuseOnly(benchmark::State& st) {
    auto& s = scene(200);
    for (auto _ : st)
        benchmark::DoNotOptimize(
            mapping::fuseGrids(s.laser, s.range2, 0.7, 0.2).cells.data());
}
BENCHMARK(BM_FuseOnly)->Unit(benchmark::kMicrosecond);

/** The planning field alone (clearance, frontier, open frontier, map edge):
 * /0 the distance to the ways on everywhere, /1 only as far as the
 * controller's band, /2 that and the clearance only as far as the widest
 * inflation + 0.5 m (as CAdaptiveSpeedPipeline computes it when the last
 * target was not the goal), /3 that clearance alone (the ways on left to
 * their first read, as the pipeline computes it when the target was the
 * goal). */
void BM_PlanningFieldOnly(benchmark::State& st) {
    auto& s = scene(200);
    const auto fused = mapping::fuseGrids(s.laser, s.range2, 0.7, 0.2);
    const speed::CAdaptiveSpeedController ctrl(s.ex.speed, 0.25,
                                               s.ex.necessaryObservations());
    const double reach =
        st.range(0) ? ctrl.wayOnBand(0.05) : std::numeric_limits<double>::infinity();
    const double clearanceReach = st.range(0) >= 2
                                      ? 0.25 + s.ex.speed.margins.front() + 0.5
                                      : std::numeric_limits<double>::infinity();
    for (auto _ : st)
        benchmark::DoNotOptimize(speed::computePlanningField(fused, 0.25, reach,
                                                             clearanceReach, {},
                                                             st.range(0) != 3)
                                     .clearance.data());
}
BENCHMARK(BM_PlanningFieldOnly)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond);

/** The decision alone (target choice + four A* plans), straight-line rule. */
void BM_DecideOnly(benchmark::State& st) {
    auto& s = scene(200);
    auto fused = mapping::fuseGrids(s.laser, s.range2, 0.7, 0.2);
    speed::markFootprintFree(fused, s.pose, 0.25);
    const speed::CAdaptiveSpeedController ctrl(s.ex.speed, 0.25,
                                               s.ex.necessaryObservations());
    const auto field = speed::computePlanningField(fused, 0.25, ctrl.wayOnBand(0.05));
    for (auto _ : st)
        benchmark::DoNotOptimize(ctrl.decide(field, s.pose, {15.5, 7.0}).speed);
}
BENCHMARK(BM_DecideOnly)->Unit(benchmark::kMillisecond);

/** The memory alone: update from the 10 m local map and the cost on. */
void BM_MemoryUpdateAndCostOn(benchmark::State& st) {
    auto& s = scene(200);
    const auto fused = mapping::fuseGrids(s.laser, s.range2, 0.7, 0.2);
    mapping::CFreeSpaceMemory memory(s.ex.explore.memory_size,
                                     s.ex.explore.memory_resolution, 3.0, 7.0);
    for (auto _ : st) {
        memory.update(fused);
        memory.computeCostToGoal({15.5, 7.0}, 2.0, fused, 0.25);
        benchmark::DoNotOptimize(memory.costToGoal(8.0, 7.0, 0.45));
    }
}
BENCHMARK(BM_MemoryUpdateAndCostOn)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
