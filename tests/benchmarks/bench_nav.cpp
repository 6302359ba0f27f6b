// One navigationStep() of MRPT's bare reactive engine against risknav's
// CRiskAwareReactiveNav with all three speed limiters (afraid map, adaptive
// speed control, stopping distance) and with none, side by side on the same
// world and config (issue: the risk-aware step <= 1.5 x the bare step, >= 300
// steps/s without navlog). datasets/office, MRPT's shipped
// reactive2d_config.ini, MRPT's simulated clock, a route through the office
// driven to and fro; no navlog.
//
// What is timed: navigationStep() alone (sensing the world's laser through
// CSimRobotInterface, MRPT's PTG evaluation, the limiters). The world's
// stepping for the nav period (4 x 0.05 s) and the route's restart when a
// goal is reached run between PauseTiming() and ResumeTiming(), so every
// iteration is one real navigating step. Times are wall-clock
// (UseRealTime()); steps_per_s = iterations / timed wall time. The adaptive
// limiter's cycle runs on a worker thread beside MRPT's evaluation (its
// worker_thread default) and ends within the step: the CPU column is the
// benchmark thread's alone; cpu_us_all_threads is the process's CPU time
// over the timed steps (both threads) per step.
//
// BM_RiskAwareStep_GlobalPlanner: the stopping-distance limiter and the
// global planner (risknav-navigate's default, global_planner = grid): its
// replans on a new leg and as the run needs, and its guide point.
//
// BM_LimiterCall/<name>: one limit() call of a separate instance of each
// limiter, loaded from the same config, on the input the all-limiters
// navigator built this cycle (its pose, obstacles, scans, target, time),
// timed by hand (UseManualTime()); the navigator's step runs untimed.
//
// The same states (counters bare_same_states_us, ratio_same_states): each
// step of the risk-aware navigator is paired with a step, just before it,
// of a bare MRPT navigator (the same config and route) on a twin world kept
// in lockstep: stepped with the risk-aware navigator's commands (the twin's
// own are dropped), sensed once a step like it, so the same pose, speeds,
// time and scans (noise included); a twin found out of step is copied from
// the world (pair_resyncs). So both engines are timed at the very states
// of one trajectory, alternately, in one run; the independent bare run
// above drives its own (faster) trajectory, meeting fewer obstacles per
// step. The twin's step is timed by hand (steady_clock) outside the
// benchmark's timing, after the adaptive limiter's worker is idle: a cycle
// of n >= 2 runs on across steps, and the wait for it is timed as part of
// the risk-aware step (its work would otherwise be done in the untimed
// twin step). Only the world's stepping (after(), after_us) stays untimed
// beside such a cycle. pair_restarts: times the twin was not navigating and
// was given the leg again.
//
// Counters: legs = route legs completed, resets = the world reset after a
// navigation error or a leg over 300 s (0 expected), after_us = the untimed
// world stepping per step, lim_<name> = share of
// commanded cycles that limiter limited. RISKNAV_BENCH_NAV_CONFIG (ini text)
// is appended to the config, e.g. to try a limiter option
// ($'[CAdaptiveSpeedLimiter]\ncycle_decimation = 2': its cycle on every
// other sensing). A reset ends MRPT's navigation before the world starts
// again (see resetWorld()).
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/CSpeedLimiter.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/sim/CSimRobotInterface.h>
#include <risknav/sim/CSimWorld.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/Clock.h>
#include <mrpt/math/CPolygon.h>
#include <mrpt/nav/reactive/CReactiveNavigationSystem.h>
#include <mrpt/system/filesystem.h>

#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace risknav;
using mrpt::math::TPose2D;
namespace fs = std::filesystem;

namespace {
const std::string kSource = RISKNAV_SOURCE_DIR;
const TPose2D kStart(3.0, 3.0, M_PI / 2);
constexpr double kT0 = 1.6e9;  // UNIX time of world time 0 on MRPT's clock
constexpr double kSimDt = 0.05;
constexpr int kStepsPerCycle = 4;    // nav period 0.2 s
constexpr int kMaxLegCycles = 1500;  // a leg not done in 300 s: reset the world
const char* kAllLimiters =
    "CAfraidSpeedLimiter CAdaptiveSpeedLimiter CStoppingDistanceLimiter";

// Out of the lower-left room through its door, along the corridor, through
// the lower-right room's door to its far corner (datasets/office/navigate.ini).
// Corridor waypoints 2.5-3 m apart: MRPT's purely reactive engine keeps its
// target in sight (with 7 m legs it now and then wandered through an upper
// door and got stuck behind the corridor wall).
const std::vector<std::pair<double, double>> kRoute = {
    {3.0, 6.6},  {6.0, 6.6},  {9.0, 6.6},  {12.0, 6.6},
    {14.5, 6.6}, {16.5, 6.6}, {16.5, 4.6}, {15.0, 2.5}};

// A scratch directory for the .afraid file and MRPT's PTG cache, removed at exit.
struct TScratch {
    std::string dir;
    TScratch() {
        dir = (fs::temp_directory_path() /
               ("risknav_bench_nav." + std::to_string(getpid())))
                  .string();
        fs::create_directories(dir + "/ptg");
    }
    ~TScratch() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};
TScratch& scratch() {
    static TScratch s;
    return s;
}

sim::CSimWorld& officeWorld(sim::CSimWorld& w) {
    common::CIniConfig cfg(kSource + "/datasets/office/world.ini");
    w.loadFromConfigFile(cfg);
    w.agents.walkers.clear();  // deterministic: no colleague in the corridor
    return w;
}

// A .afraid file on the office map's geometry: 20 runs along the route, an
// obstacle bursting out at each of the two doors on every other run.
const std::string& afraidFile() {
    static const std::string path = [] {
        sim::CSimWorld w;
        officeWorld(w);
        afraid::CAfraidGrid g(w.grid());
        for (int run = 0; run < 20; run++) {
            g.addPass(kStart.x, kStart.y);
            double x = kStart.x, y = kStart.y;
            for (const auto& [nx, ny] : kRoute) {
                g.addTraversal(x, y, nx, ny);
                x = nx;
                y = ny;
            }
            if (run % 2 == 0) {
                g.addObstacleEvent(3.0, 5.9);   // the lower-left room's door
                g.addObstacleEvent(16.5, 5.9);  // the lower-right room's door
                g.addRobotEvent(3.0, 5.5);
            }
            g.runs++;
        }
        const std::string p = scratch().dir + "/office.afraid";
        g.save(p);
        return p;
    }();
    return path;
}

// MRPT's shipped reactive2d_config.ini plus risknav's sections.
std::string navConfig(const std::string& limiters) {
    std::ifstream f(mrpt::system::find_mrpt_shared_dir() +
                    "config_files/navigation-ptgs/reactive2d_config.ini");
    std::stringstream ss;
    ss << f.rdbuf() << "\n"
       << "[CRiskAwareReactiveNav]\nspeed_limiters = " << limiters << "\n"
       << "[CAfraidSpeedLimiter]\nafraid_file = " << afraidFile() << "\n"
       << "[CStoppingDistanceLimiter]\nmargin = 0.1\nlateral_margin = 0.05\n"
       << "[CAdaptiveSpeedLimiter]\n"  // its defaults
       << "[Robot]\nradius = 0.25\nmax_v = 1.1\naccel = 1.0\ndecel = 1.0\n";
    // e.g. "[CAdaptiveSpeedLimiter]\nlocal_map_resolution = 0.1" to try an option
    if (const char* extra = std::getenv("RISKNAV_BENCH_NAV_CONFIG"))
        ss << "\n" << extra << "\n";
    return ss.str();
}

// The twin's robot interface: the world it senses is driven by another
// navigator's commands, so its own are dropped.
class CDroppedCommands : public sim::CSimRobotInterface {
  public:
    using sim::CSimRobotInterface::CSimRobotInterface;
    bool changeSpeeds(const mrpt::kinematics::CVehicleVelCmd&) override { return true; }
    bool stop(bool) override { return true; }
};

// The risk-aware navigator, with what its generate_vel_cmd() gives its
// limiters readable from outside (for BM_LimiterCall).
class CProbeNav : public nav::CRiskAwareReactiveNav {
  public:
    using nav::CRiskAwareReactiveNav::CRiskAwareReactiveNav;
    common::TSpeedLimitInput limiterInput(const sim::CSimRobotInterface&,
                                          double desired) const {
        // The navigator's own input (without MRPT's trajectory, which it
        // only has inside its step).
        return nav::CRiskAwareReactiveNav::limiterInput(nullptr, desired);
    }
};

// A world, its robot interface and a navigator driving the route to and fro.
struct TNavBench {
    sim::CSimWorld world;
    std::unique_ptr<sim::CSimRobotInterface> robotIf;
    std::unique_ptr<mrpt::nav::CReactiveNavigationSystem> nav;
    CProbeNav* risk = nullptr;  // nav, when it is the risk-aware one
    bool forward = true;
    double clockBase = kT0;  // UNIX time of world time 0: MRPT's clock never goes back
    int legCycles = 0;
    long legs = 0, resets = 0, cycles = 0, commanded = 0;
    std::map<std::string, long> wins;  // limiter -> cycles it limited
    /** The bare twin of a risk-aware navigator (see the header). */
    struct TTwin {
        sim::CSimWorld world;  // in lockstep with the risk-aware navigator's
        std::unique_ptr<sim::CSimRobotInterface> robotIf;
        std::unique_ptr<mrpt::nav::CReactiveNavigationSystem> nav;
        double seconds = 0;
        long steps = 0, restarts = 0, resyncs = 0;
        void resetCounts() { seconds = 0, steps = restarts = resyncs = 0; }
    };
    std::unique_ptr<TTwin> twin;
    /** BM_LimiterCall's separate limiter instances (fed every commanded cycle). */
    std::vector<std::pair<std::string, common::CSpeedLimiter::Ptr>> probes;

    // MRPT's navigator on `robot`, configured as the benchmark's (limiters:
    // nullptr = the bare MRPT engine).
    std::unique_ptr<mrpt::nav::CReactiveNavigationSystem> makeNav(
        sim::CSimRobotInterface& robot, const char* limiters) {
        std::unique_ptr<mrpt::nav::CReactiveNavigationSystem> n;
        if (limiters) {
            auto r = std::make_unique<CProbeNav>(robot);
            risk = r.get();
            n = std::move(r);
        } else {
            n = std::make_unique<mrpt::nav::CReactiveNavigationSystem>(robot);
        }
        n->setMinLoggingLevel(mrpt::system::LVL_ERROR);
        const_cast<mrpt::system::CTimeLogger&>(n->getDelaysTimeLogger()).disable();
        mrpt::config::CConfigFileMemory cfg(navConfig(limiters ? limiters : ""));
        n->loadConfigFile(cfg);
        n->params_abstract_ptg_navigator.ptg_cache_files_directory =
            scratch().dir + "/ptg";
        mrpt::math::CPolygon shape;
        for (int i = 0; i < 16; i++)
            shape.AddVertex(world.robot.radius * std::cos(i * M_PI / 8),
                            world.robot.radius * std::sin(i * M_PI / 8));
        n->changeRobotShape(shape);
        n->initialize();
        return n;
    }

    explicit TNavBench(const char* limiters, bool globalPlanner = false) {
        officeWorld(world);
        world.reset(kStart, 11, clockBase);
        robotIf = std::make_unique<sim::CSimRobotInterface>(world);
        robotIf->setMinLoggingLevel(mrpt::system::LVL_ERROR);
        nav = makeNav(*robotIf, limiters);
        if (globalPlanner && risk) {
            // risknav-navigate's default: the global plan on the office map,
            // replanned as the run needs (the engine's disc: the robot's)
            auto p = std::make_shared<planning::CGlobalPlanner>();
            p->setMap(world.grid(), world.distanceField().rule(), world.robot.radius);
            risk->setGlobalPlanner(p);
        }
        if (limiters) {
            twin = std::make_unique<TTwin>();
            twin->world = world;
            twin->robotIf = std::make_unique<CDroppedCommands>(twin->world);
            twin->robotIf->setMinLoggingLevel(mrpt::system::LVL_ERROR);
            twin->nav = makeNav(*twin->robotIf, nullptr);
        }
        startLeg();
        for (int i = 0; i < 10; i++) {  // warm up (first cycles, caches)
            step();
            after();
        }
        legs = resets = cycles = commanded = 0;
        wins.clear();
        if (twin)
            twin->resetCounts();
    }

    void syncClock() const { mrpt::Clock::setSimulatedTime(world.timestamp()); }

    void startLeg() {
        mrpt::nav::TWaypointSequence wps;
        if (forward) {
            for (const auto& [x, y] : kRoute)
                wps.waypoints.emplace_back(x, y, 0.3, false);
        } else {
            for (size_t i = kRoute.size() - 1; i-- > 0;)
                wps.waypoints.emplace_back(kRoute[i].first, kRoute[i].second, 0.3, false);
            wps.waypoints.emplace_back(kStart.x, kStart.y, 0.3, false);
        }
        syncClock();
        nav->navigateWaypoints(wps);
        if (twin)
            twin->nav->navigateWaypoints(wps);
        leg = wps;
        legCycles = 0;
    }
    mrpt::nav::TWaypointSequence leg;  ///< the leg's waypoints

    // Timed: a cycle of the adaptive limiter still in flight (n >= 2 runs
    // one on across steps) ends before the untimed twin step; left to end
    // there, its work went untimed (cycle_decimation = 2 then
    // measured 1.0x with the whole process's CPU per step at the bare step's).
    void finishWorker() {
        if (!risk)
            return;
        for (const auto& l : risk->limiters())
            if (auto* a = dynamic_cast<nav::CAdaptiveSpeedLimiter*>(l.get()))
                (void)a->pipeline();  // waits for a cycle in flight
    }

    // Untimed: the bare twin's step at the state the next step() will see
    // (the worker idle: finishWorker() ran in the timed part).
    void twinStep() {
        finishWorker();
        const TPose2D p = world.truePose(), q = twin->world.truePose();
        if (p.x != q.x || p.y != q.y || p.phi != q.phi ||
            world.time() != twin->world.time() || world.speed() != twin->world.speed()) {
            twin->world = world;
            twin->resyncs++;
        }
        syncClock();
        if (twin->nav->getCurrentState() != mrpt::nav::CAbstractNavigator::NAVIGATING) {
            twin->nav->cancel();
            twin->nav->navigationStep();
            twin->nav->navigateWaypoints(leg);
            twin->restarts++;
        }
        const auto t0 = std::chrono::steady_clock::now();
        twin->nav->navigationStep();
        twin->seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        twin->steps++;
    }

    void resetWorld() {
        // MRPT's navigator was made for one run: its navigation ends (an
        // idle step) so that the next starts afresh (its pose history, its
        // last command, the robot time of its last pose update: the world's
        // time starts again at 0; left as they were, MRPT ignored every pose
        // until the new time passed the old one and drove from the old pose)
        nav->cancel();
        syncClock();
        nav->navigationStep();
        if (twin) {
            twin->nav->cancel();
            twin->nav->navigationStep();
        }
        clockBase += world.time() + 10;
        world.reset(kStart, 11 + uint64_t(resets), clockBase);
        if (twin)
            twin->world = world;
        forward = true;
        resets++;
        if (risk) {
            auto ls = risk->limiters();
            for (const auto& p : probes)
                ls.push_back(p.second);
            for (const auto& l : ls)
                if (auto* a = dynamic_cast<nav::CAdaptiveSpeedLimiter*>(l.get()))
                    a->reset();  // its map: the robot was teleported
        }
        startLeg();
    }

    // The timed part.
    void step() {
        syncClock();
        nav->navigationStep();
    }

    // Untimed: the route's bookkeeping and the world for one nav period.
    void after() {
        cycles++;
        legCycles++;
        if (risk && risk->lastLimit().desired > 0) {
            commanded++;
            if (!risk->lastLimit().limiter.empty())
                wins[risk->lastLimit().limiter]++;
        }
        const auto st = nav->getCurrentState();
        if (st == mrpt::nav::CAbstractNavigator::IDLE &&
            nav->getWaypointNavStatus().final_goal_reached) {
            forward = !forward;
            legs++;
            startLeg();
        } else if (st != mrpt::nav::CAbstractNavigator::NAVIGATING ||
                   legCycles > kMaxLegCycles) {
            resetWorld();
        }
        for (int k = 0; k < kStepsPerCycle; k++)
            world.step(kSimDt);
        if (twin) {  // the risk-aware navigator's command, not the twin's
            twin->world.command(world.commandedSpeed(), world.commandedTurnRate());
            for (int k = 0; k < kStepsPerCycle; k++)
                twin->world.step(kSimDt);
        }
    }

    void report(benchmark::State& state) const {
        state.counters["steps_per_s"] =
            benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
        state.counters["legs"] = double(legs);
        state.counters["resets"] = double(resets);
        if (risk && commanded > 0)
            for (const auto& [name, n] : wins)
                state.counters["lim_" + name] = double(n) / double(commanded);
    }
};

// One fixture per variant for the whole run: the route goes on across
// repetitions (building a navigator, i.e. MRPT's PTGs, is not what is measured).
TNavBench& fixture(const std::string& variant) {
    static std::map<std::string, std::unique_ptr<TNavBench>> all;
    auto& f = all[variant];
    if (!f) {
        mrpt::Clock::setActiveClock(mrpt::Clock::Simulated);
        if (variant == "bare")
            f = std::make_unique<TNavBench>(nullptr);
        else if (variant == "none")
            f = std::make_unique<TNavBench>("");
        else if (variant == "planner")
            f = std::make_unique<TNavBench>("CStoppingDistanceLimiter", true);
        else
            f = std::make_unique<TNavBench>(kAllLimiters);
    }
    return *f;
}

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

void runSteps(benchmark::State& state, TNavBench& f) {
    // this run's counts (the fixture goes on across runs)
    f.legs = f.resets = f.commanded = 0;
    f.wins.clear();
    if (f.twin)
        f.twin->resetCounts();
    double cpu = 0, wall = 0, after = 0;
    for (auto _ : state) {
        if (f.twin) {
            const double c0 = processCpuSeconds();
            const auto t0 = std::chrono::steady_clock::now();
            f.finishWorker();
            wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                        .count();
            cpu += processCpuSeconds() - c0;
            state.PauseTiming();
            f.twinStep();
            state.ResumeTiming();
        }
        const double c0 = processCpuSeconds();
        const auto t0 = std::chrono::steady_clock::now();
        f.step();
        wall +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        cpu += processCpuSeconds() - c0;
        state.PauseTiming();
        const auto a0 = std::chrono::steady_clock::now();
        f.after();
        after +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - a0).count();
        state.ResumeTiming();
    }
    state.counters["after_us"] = 1e6 * after / double(state.iterations());
    f.report(state);
    state.counters["cpu_us_all_threads"] = 1e6 * cpu / double(state.iterations());
    if (f.twin && f.twin->steps > 0) {
        const double bare = f.twin->seconds / double(f.twin->steps);
        state.counters["bare_same_states_us"] = 1e6 * bare;
        state.counters["ratio_same_states"] = wall / double(state.iterations()) / bare;
        state.counters["pair_restarts"] = double(f.twin->restarts);
        state.counters["pair_resyncs"] = double(f.twin->resyncs);
    }
}

void BM_BareEngineStep(benchmark::State& state) {
    runSteps(state, fixture("bare"));
}
void BM_RiskAwareStep_NoLimiters(benchmark::State& state) {
    runSteps(state, fixture("none"));
}
void BM_RiskAwareStep_AllLimiters(benchmark::State& state) {
    runSteps(state, fixture("all"));
}
void BM_RiskAwareStep_GlobalPlanner(benchmark::State& state) {
    runSteps(state, fixture("planner"));
}
BENCHMARK(BM_BareEngineStep)->Unit(benchmark::kMicrosecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_RiskAwareStep_GlobalPlanner)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_RiskAwareStep_NoLimiters)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_RiskAwareStep_AllLimiters)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime()
    ->MinTime(2.0);

// One limit() call of a separate instance of `name`, loaded from the same
// config, on the input the all-limiters navigator (its own fixture) built for
// this cycle. Every probe instance is called on every commanded cycle (the
// adaptive limiter keeps a map and measures its cycle), only `name` is timed.
TNavBench& probeFixture() {
    TNavBench& f = fixture("probe");
    if (f.probes.empty()) {
        nav::registerAllClasses_nav();
        mrpt::config::CConfigFileMemory cfg(navConfig(kAllLimiters));
        std::istringstream names(kAllLimiters);
        for (std::string n; names >> n;) {
            auto l = common::CSpeedLimiter::Factory(n);
            l->loadConfig(cfg, n);
            f.probes.emplace_back(n, l);
        }
    }
    return f;
}

void BM_LimiterCall(benchmark::State& state, const std::string& name) {
    TNavBench& f = probeFixture();
    for (auto _ : state) {
        // Steps until MRPT commands a forward speed (else no limiter is asked).
        do {
            f.step();
            f.after();
        } while (!(f.risk->lastLimit().desired > 0));
        // The input of the step just taken (pose, obstacles, scans, target and
        // clock as the navigator's own limiters saw them).
        const auto in = f.risk->limiterInput(*f.robotIf, f.risk->lastLimit().desired);
        for (const auto& [n, l] : f.probes) {
            if (n != name) {
                benchmark::DoNotOptimize(l->limit(in));
                continue;
            }
            const auto t0 = std::chrono::steady_clock::now();
            auto lim = l->limit(in);
            const auto t1 = std::chrono::steady_clock::now();
            benchmark::DoNotOptimize(lim);
            state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
        }
    }
    state.counters["calls_per_s"] =
        benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
const bool kLimiterCalls = [] {
    std::istringstream names(kAllLimiters);
    for (std::string n; names >> n;)
        benchmark::RegisterBenchmark(("BM_LimiterCall/" + n).c_str(), BM_LimiterCall, n)
            ->Unit(benchmark::kMicrosecond)
            ->UseManualTime()
            ->Iterations(500);
    return true;
}();
}  // namespace

BENCHMARK_MAIN();
