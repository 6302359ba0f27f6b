#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/speed/TExploreOptions.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <vector>

using namespace risknav::common;

namespace risknav::nav {
IMPLEMENTS_MRPT_OBJECT(CAdaptiveSpeedLimiter, risknav::common::CSpeedLimiter,
                       risknav::nav)

namespace {
/** How many intervals the measured cycle is the median of. */
constexpr size_t kIntervals = 16;

double median(const std::deque<double>& d) {
    std::vector<double> v(d.begin(), d.end());
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The built-in models: a laser (N = 2) and a stereo-like sensor (N = 5).
mapping::TSensorModel defaultLaser() {
    mapping::TSensorModel m;
    m.p_obs_given_obstacle = 0.7;
    m.p_obs_given_free = 0.3;
    return m;
}
}  // namespace

CAdaptiveSpeedLimiter::TOptions::TOptions() : laser(defaultLaser()) {
    section = speed.section = "CAdaptiveSpeedLimiter";
    laser.section = section + " (built-in laser_model)";
    range2.section = section + " (built-in range2_model)";
}

void CAdaptiveSpeedLimiter::TOptions::declare(Visitor& v) {
    v.include(speed);  // the keys of [SpeedControl], in this section
    v.flag(measure_cycle_time, "measure_cycle_time",
           "T is the measured cycle (else cycle_time)");
    v.integer(fixed_speed_index, "fixed_speed_index",
              TRange::closed(-1, double(speed.speeds.size()) - 1),
              "-1: adaptive; k: fixed at candidate k (the fixed-speed baseline)");
    v.text(laser_model, "laser_model", false,
           "section of the laser's model ('' = built-in)");
    v.text(range2_model, "range2_model", false,
           "section of the second sensor's model ('' = built-in)");
    v.flag(use_range2, "use_range2", "fuse the second range sensor");
    v.number(local_map_size, "local_map_size", TRange::closed(2, 100, "m"),
             "side of the local grid");
    v.number(local_map_resolution, "local_map_resolution", TRange::closed(0.01, 0.5, "m"),
             "cell size of the local grid");
    v.number(memory_size, "memory_size", TRange::closed(0, 1000, "m"),
             "side of the remembered map (0 = none)");
    v.number(memory_resolution, "memory_resolution", TRange::closed(0.05, 5, "m"),
             "cell size of the remembered map");
    v.flag(worker_thread, "worker_thread", "observed cycles beside the engine");
    v.integer(cycle_decimation, "cycle_decimation", TRange::closed(1, 100),
              "a cycle every n-th sensing");
    v.namedSection(laser, laser_model, "laser_model");
    v.namedSection(range2, range2_model, "range2_model", use_range2);
}

void CAdaptiveSpeedLimiter::TOptions::validateRules() const {
    const std::string& s = section;
    speed::checkLocalMapSizes(s, local_map_size, local_map_resolution, memory_size,
                              memory_resolution);
    // N of (000) section 3.2 must exist for each fused model
    for (const auto* m : {&laser, use_range2 ? &range2 : &laser})
        try {
            (void)mapping::necessaryObservations(*m, speed.free_threshold);
        } catch (const std::invalid_argument& e) {
            throw CConfigKeyError(
                m->section, "p_obs_given_obstacle", numberText(m->p_obs_given_obstacle),
                std::string(e.what()) +
                    " with free_threshold = " + numberText(speed.free_threshold));
        }
}

void CAdaptiveSpeedLimiter::loadConfig(const mrpt::config::CConfigFileBase& c,
                                       const std::string& section) {
    static const std::set<std::string> known = {"speeds",
                                                "margins",
                                                "gap_threshold",
                                                "lookahead_cycles",
                                                "occupied_threshold",
                                                "free_threshold",
                                                "frontier_goal_weight",
                                                "target_switch_cost",
                                                "cycle_time",
                                                "measure_cycle_time",
                                                "fixed_speed_index",
                                                "laser_model",
                                                "range2_model",
                                                "use_range2",
                                                "local_map_size",
                                                "local_map_resolution",
                                                "memory_size",
                                                "memory_resolution",
                                                "worker_thread",
                                                "cycle_decimation"};
    std::vector<std::string> keys;
    c.getAllKeys(section, keys);
    for (const auto& k : keys)
        if (!known.count(k))
            throwBadKey(c, section, k, c.read_string(section, k, ""),
                        "unknown key (known: speeds margins gap_threshold "
                        "lookahead_cycles occupied_threshold free_threshold "
                        "frontier_goal_weight target_switch_cost cycle_time "
                        "measure_cycle_time fixed_speed_index laser_model range2_model "
                        "use_range2 "
                        "local_map_size local_map_resolution memory_size "
                        "memory_resolution worker_thread cycle_decimation)");
    TOptions o;
    loadOptions(o, c, section);
    reset();  // no cycle runs on the old options
    options = o;
}

void CAdaptiveSpeedLimiter::saveConfig(mrpt::config::CConfigFileBase& c,
                                       const std::string& section) const {
    options.saveToConfigFile(c, section);
}

void CAdaptiveSpeedLimiter::reset() {
    try {
        waitCycle();
    } catch (const std::exception&) {
        // its result is dropped with the rest of the run
    }
    resetState();
}

void CAdaptiveSpeedLimiter::resetState() const {
    m_pipeline.reset();
    m_lastLaser.reset();
    m_lastRange2.reset();
    m_dtLaser.clear();
    m_dtRange2.clear();
    m_previousTarget.reset();
    m_cycleIn = TCycleInput{};
    m_result = TCycleResult{};
    m_adopted = TCycleResult{};
    m_inFlight = false;
    m_sensings = 0;
    m_lastSensing.reset();
    m_lastTarget.reset();
    m_retargeted = false;
    m_radius = 0;
    m_keptLaser.reset();
    m_keptRange2.reset();
    m_observed.reset();
}

speed::CAdaptiveSpeedPipeline::TParams CAdaptiveSpeedLimiter::params(double radius,
                                                                     double T) const {
    speed::CAdaptiveSpeedPipeline::TParams p;
    p.speed = options.speed;
    p.speed.cycle_time = T;
    p.laserModel = options.laser;
    p.range2Model = options.range2;
    p.useRange2 = options.use_range2;
    p.robotRadius = radius;
    p.localMapSize = options.local_map_size;
    p.localMapResolution = options.local_map_resolution;
    p.memorySize = options.memory_size;
    p.memoryResolution = options.memory_resolution;
    return p;
}

int CAdaptiveSpeedLimiter::necessaryObservations() const {
    return speed::CAdaptiveSpeedPipeline::necessaryObservations(
        params(0.25, options.speed.cycle_time));
}

double CAdaptiveSpeedLimiter::cycleTime() const {
    const double fallback = options.speed.cycle_time;
    if (!options.measure_cycle_time || m_dtLaser.empty())
        return fallback;
    const double fl = options.speed.free_threshold;
    // N T = max over the fused sensors of N_s T_s (section 3.1 per sensor)
    const int nLaser = mapping::necessaryObservations(options.laser, fl);
    double nt = nLaser * median(m_dtLaser);
    int n = nLaser;
    if (options.use_range2) {
        const int n2 = mapping::necessaryObservations(options.range2, fl);
        n = std::max(n, n2);
        nt = std::max(nt, n2 * (m_dtRange2.empty() ? fallback : median(m_dtRange2)));
    }
    return std::clamp(nt / n, 1e-3, 10.0);
}

void CAdaptiveSpeedLimiter::sense(const TSpeedLimitInput& in) const {
    // a new run (the clock went back) or another robot: a new map
    if (m_lastSensing && (in.time < *m_lastSensing || in.robot->radius != m_radius)) {
        waitCycle();
        resetState();
    }
    // a new target (a waypoint reached): a cycle now, taken at once
    const bool retarget =
        m_lastSensing && (in.target.has_value() != m_lastTarget.has_value() ||
                          (in.target && (in.target->x != m_lastTarget->x ||
                                         in.target->y != m_lastTarget->y)));
    m_lastSensing = in.time;
    m_lastTarget = in.target;
    m_radius = in.robot->radius;
    // the latest scan of each sensor until a cycle takes it (copies: the
    // caller's may go before the cycle ends)
    auto keep = [&](const mrpt::obs::CObservation2DRangeScan* s,
                    std::optional<TKeptScan>& kept) {
        if (!s)
            return;
        if (!kept)
            kept.emplace();
        kept->scan = *s;
        kept->pose = in.pose;
        kept->time = in.time;
    };
    keep(in.scan, m_keptLaser);
    keep(in.scan2, m_keptRange2);
    if (retarget)
        m_sensings = 0;
    if (m_sensings++ % size_t(options.cycle_decimation) != 0)
        return;
    // a cycle's sensing: the cycle before ends (normally long since) and,
    // unless taken already, its decision is taken now
    takeCycle();
    m_retargeted = retarget;
    m_cycleIn.pose = in.pose;
    m_cycleIn.target = in.target;
    m_cycleIn.radius = m_radius;
    m_cycleIn.laser = std::move(m_keptLaser);
    m_cycleIn.range2 = std::move(m_keptRange2);
    m_keptLaser.reset();
    m_keptRange2.reset();
    if (!options.worker_thread) {
        runCycle();
        m_inFlight = true;
        return;
    }
    if (!m_worker)
        m_worker = std::make_unique<common::CWorkerThread>();
    m_inFlight = true;
    m_worker->start([this] { runCycle(); });
}

void CAdaptiveSpeedLimiter::runCycle() const {
    const TCycleInput& in = m_cycleIn;
    // the measured cycle, per sensor: intervals between the scans of it
    // that cycles took
    auto measure = [&](const std::optional<TKeptScan>& s, std::optional<double>& last,
                       std::deque<double>& dts) {
        if (!s)
            return;
        if (last && s->time > *last) {
            dts.push_back(s->time - *last);
            if (dts.size() > kIntervals)
                dts.pop_front();
        }
        last = s->time;
    };
    measure(in.laser, m_lastLaser, m_dtLaser);
    measure(in.range2, m_lastRange2, m_dtRange2);
    const double T = cycleTime();
    if (!m_pipeline) {
        m_pipeline = std::make_unique<speed::CAdaptiveSpeedPipeline>(params(in.radius, T),
                                                                     in.pose);
        // on the worker, the navigator's thread takes parts of the cycle
        // while it waits for it in limit() (CWorkerThread::parallelFor())
        if (common::CWorkerThread* w = m_worker.get())
            m_pipeline->setParallelFor(
                [w](size_t n, const std::function<void(size_t)>& body) {
                    w->parallelFor(n, body);
                });
    }
    m_pipeline->setCycleTime(T);
    TCycleResult& r = m_result;
    r.T = T;
    // (000) section 2: move the grids by the ego-motion, update, classify, fuse
    m_pipeline->update(in.pose, in.laser ? &in.laser->scan : nullptr,
                       in.laser ? in.laser->pose : in.pose,
                       in.range2 ? &in.range2->scan : nullptr,
                       in.range2 ? in.range2->pose : in.pose);
    r.creep = false;
    r.decision.reset();
    r.goal.reset();
    if (in.target) {
        // sections 3-5: the fastest safe speed on the way to the target
        const speed::TSpeedDecision d = m_pipeline->decide(
            in.pose, *in.target, options.fixed_speed_index, m_previousTarget);
        if (d.temporaryTarget && d.reason != speed::TSpeedReason::Unreachable)
            m_previousTarget = d.target;
        else
            m_previousTarget.reset();
        r.decision = d;
        r.goal = *in.target;
        r.creep = m_pipeline->heldLongEnough(d.speed <= 0);
    }
    r.field = m_pipeline->takeField();  // guidePoint() reads it while the next cycle runs
}

void CAdaptiveSpeedLimiter::waitCycle() const {
    if (!m_worker)
        return;
    try {
        m_worker->wait();
    } catch (...) {
        m_inFlight = false;  // its result is not to be taken
        throw;
    }
}

void CAdaptiveSpeedLimiter::takeCycle() const {
    waitCycle();
    if (m_inFlight)
        adopt();
}

void CAdaptiveSpeedLimiter::adopt() const {
    std::swap(m_adopted, m_result);
    m_adopted.valid = true;
    m_inFlight = false;
    m_retargeted = false;
}

void CAdaptiveSpeedLimiter::impl_observe(const TSpeedLimitInput& in) const {
    m_observed = in.time;
    sense(in);
}

void CAdaptiveSpeedLimiter::finishObserved() const {
    // a new target's cycle is taken by the end of its step also when the
    // engine called no limit(): the next step's turn and guide point use it
    if (options.cycle_decimation == 1 || m_retargeted)
        takeCycle();
}

TSpeedLimit CAdaptiveSpeedLimiter::impl_limit(const TSpeedLimitInput& in) const {
    // observe() saw this sensing (same time); otherwise (a caller that does
    // not observe) this call is the sensing
    if (!(m_observed && *m_observed == in.time))
        sense(in);
    m_observed.reset();
    // the cycle's decision now: always with cycle_decimation = 1, for the
    // first cycle of a run and for a new target's
    if (options.cycle_decimation == 1 || !m_adopted.valid || m_retargeted)
        takeCycle();
    if (!m_adopted.decision)
        return {in.desiredSpeed, ""};
    const speed::TSpeedDecision& d = *m_adopted.decision;
    double v = d.speed;
    char why[160];
    const bool creep = m_adopted.creep;
    if (creep)
        v = options.fixed_speed_index >= 0
                ? options.speed.speeds[size_t(options.fixed_speed_index)]
                : options.speed.speeds.back();
    if (v >= in.desiredSpeed)
        return {in.desiredSpeed, ""};
    const int N = necessaryObservations();
    switch (d.reason) {
        case speed::TSpeedReason::Narrow:
            std::snprintf(why, sizeof(why),
                          "narrow passage: %.2f m/s is the fastest speed whose margin "
                          "passes (gap rule)",
                          v);
            break;
        case speed::TSpeedReason::Undecided:
            std::snprintf(why, sizeof(why), "undecided region %.2f m ahead",
                          d.dUndecided);
            break;
        case speed::TSpeedReason::Unreachable:
            std::snprintf(why, sizeof(why), "unreachable");
            break;
        case speed::TSpeedReason::None:
            std::snprintf(why, sizeof(why), "fastest candidate speed %.2f m/s", v);
            break;
    }
    std::string reason = why;
    if (creep)
        reason += " (held " + std::to_string(N) + " cycles: creeping)";
    return {v, reason};
}

std::optional<mrpt::math::TPoint2D> CAdaptiveSpeedLimiter::guidePoint(
    const mrpt::math::TPose2D& pose, double lookahead) const {
    // the decision limit() uses, on the field it planned on (a cycle after it
    // may be running)
    const auto& last = m_adopted.decision;
    if (!last || last->reason == speed::TSpeedReason::Unreachable ||
        last->path.points.size() < 2)
        return std::nullopt;
    const auto& field = m_adopted.field;
    if (const auto& goal = m_adopted.goal) {
        // the straight line to the goal is open on the map (known free with
        // the robot's radius to spare, up to where the map ends): no guide,
        // MRPT goes straight (it is tuned for that; led along a path that
        // hugs one side of a narrow passage it froze at the entrance)
        const double dx = goal->x - pose.x, dy = goal->y - pose.y;
        const double len = std::hypot(dx, dy), res = field.map.resolution;
        bool open = true;
        for (int k = 1, n = int(std::ceil(len / (0.5 * res))); open && k <= n; k++) {
            const double x = pose.x + dx * k / n, y = pose.y + dy * k / n;
            if (!field.map.inside(field.map.x2idx(x), field.map.y2idx(y)))
                break;
            open = field.clearanceAt(x, y) >= m_radius;
        }
        if (open)
            return std::nullopt;
    }
    const auto& path = last->path;
    return path
        .points[speed::lookaheadPoint(path, field, {pose.x, pose.y}, lookahead).ahead];
}

}  // namespace risknav::nav
