#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/CFreeSpaceMemory.h>
#include <risknav/mapping/free_space.h>
#include <risknav/mapping/scan_points.h>
#include <risknav/sim/CClosedLoop.h>
#include <risknav/speed/CExplorer.h>

#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPoint2D.h>
#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;

namespace risknav::speed {
bool TModeResult::allReached() const {
    return std::all_of(destinationStatus.begin(), destinationStatus.end(),
                       [](const std::string& s) { return s == "reached"; });
}

void CExplorer::loadFromConfigFile(const CIniConfig& c, std::optional<uint64_t> seed) {
    static const std::set<std::string> known = {"Explore",
                                                "SpeedControl",
                                                "MapLaser",
                                                "MapRange2",
                                                "CStoppingDistanceLimiter",
                                                "World",
                                                "Robot",
                                                "Odometry",
                                                "Laser",
                                                "RangeSensor2",
                                                "ScanMatching"};
    for (const auto& s : c.sections())
        if (!known.count(s) && !sim::CAgentsSim::ownsSection(s))
            c.throwUnknownSection(
                s,
                "Explore, SpeedControl, MapLaser, MapRange2, "
                "CStoppingDistanceLimiter, ScanMatching, World, Robot, Odometry, Laser, "
                "RangeSensor2, CorridorWalkerN, DoorPedestrianN, ClutterN");
    for (const char* s : {"Explore", "World"})
        if (!c.sectionExists(s))
            throw CBadInputError(c.path() + ": missing section [" + s + "]");
    loadOptions(explore, c, "Explore");
    if (seed)
        explore.seed = *seed;
    loadOptions(speed, c, "SpeedControl");
    laserModel.p_obs_given_obstacle = 0.7;  // a laser's defaults (N = 2)
    laserModel.p_obs_given_free = 0.3;
    loadOptions(laserModel, c, "MapLaser");
    loadOptions(range2Model, c, "MapRange2");
    loadOptions(stopRule.options, c, "CStoppingDistanceLimiter");
    loadOptions(scanMatch, c, "ScanMatching");
    world.loadFromConfigFile(c);
    c.throwOnUnreadKeys();
    // what the world says about the run
    if (speed.speeds.front() > world.robot.max_v + 1e-12)
        throwBadKey(
            c, "SpeedControl", "speeds", numberText(speed.speeds.front()),
            "the fastest speed exceeds [Robot] max_v = " + numberText(world.robot.max_v));
    const auto& g = world.grid();
    auto check = [&](const std::string& key, double x, double y) {
        char b[200];
        if (x < g.getXMin() || x > g.getXMax() || y < g.getYMin() || y > g.getYMax()) {
            std::snprintf(b, sizeof(b),
                          "(%.2f, %.2f) is outside the world [%.1f, %.1f] x [%.1f, %.1f]",
                          x, y, g.getXMin(), g.getXMax(), g.getYMin(), g.getYMax());
            throwBadKey(c, "Explore", key, readString(c, "Explore", key, ""), b);
        }
        // in metres, as every app checks a start (CSimWorld::placement());
        // the clutter the map does not hold is checked at the start only
        const auto pl = world.placement(x, y);
        if (!pl.free() && (key == "start" || pl.with == "the map"))
            throwBadKey(c, "Explore", key, readString(c, "Explore", key, ""),
                        pointText(x, y) + " " + pl.why);
    };
    check("start", explore.start[0], explore.start[1]);
    // people and clutter against the map (as every app that steps the world)
    world.checkAgentsAgainstMap(c);
    for (size_t k = 0; k + 1 < explore.destinations.size(); k += 2)
        check("destinations", explore.destinations[k], explore.destinations[k + 1]);
    // N must exist for each model (validate() cannot know the free threshold)
    for (const auto& [sec, model] :
         {std::pair<const char*, const mapping::TSensorModel*>("MapLaser", &laserModel),
          {"MapRange2", &range2Model}}) {
        try {
            (void)mapping::necessaryObservations(*model, speed.free_threshold);
        } catch (const std::invalid_argument& e) {
            throwBadKey(
                c, sec, "p_obs_given_obstacle", numberText(model->p_obs_given_obstacle),
                std::string(e.what()) +
                    " with p_obs_given_free = " + numberText(model->p_obs_given_free) +
                    " and [SpeedControl] free_threshold = " +
                    numberText(speed.free_threshold));
        }
    }
}

void CExplorer::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    explore.saveToConfigFile(c, "Explore");
    speed.saveToConfigFile(c, "SpeedControl");
    laserModel.saveToConfigFile(c, "MapLaser");
    range2Model.saveToConfigFile(c, "MapRange2");
    stopRule.options.saveToConfigFile(c, "CStoppingDistanceLimiter");
    scanMatch.saveToConfigFile(c, "ScanMatching");
    world.saveToConfigFile(c);
}

CAdaptiveSpeedPipeline::TParams CExplorer::pipelineParams() const {
    CAdaptiveSpeedPipeline::TParams p;
    p.speed = speed;
    p.laserModel = laserModel;
    p.range2Model = range2Model;
    p.useRange2 = world.range2.options.enabled;
    p.robotRadius = world.robot.radius;
    p.localMapSize = explore.local_map_size;
    p.localMapResolution = explore.local_map_resolution;
    p.memorySize = memorySize();
    p.memoryResolution = explore.memory_resolution;
    return p;
}

double exploreMemorySize(double configured, double resolution, double localMapSize,
                         const mrpt::math::TPoint2D& start,
                         const std::vector<double>& destinations, int maxCells) {
    if (!(configured > 0))
        return 0;
    double farthest = 0;
    for (size_t k = 0; k + 1 < destinations.size(); k += 2)
        farthest = std::max(farthest, std::hypot(destinations[k] - start.x,
                                                 destinations[k + 1] - start.y));
    const double needed = 2 * (farthest + localMapSize);
    // one cell short of the cap: (cells x resolution) / resolution may round up
    return std::max(configured, std::min(needed, (maxCells - 1) * resolution));
}

double CExplorer::memorySize() const {
    if (explore.start.size() < 2)
        return explore.memory_size;
    return exploreMemorySize(explore.memory_size, explore.memory_resolution,
                             explore.local_map_size, {explore.start[0], explore.start[1]},
                             explore.destinations);
}

int CExplorer::necessaryObservations() const {
    return CAdaptiveSpeedPipeline::necessaryObservations(pipelineParams());
}

TPose2D CExplorer::egoPose() const {
    if (explore.ego_motion == "ground_truth")
        return world.truePose();
    if (m_localizer)
        return m_localizer->predict(world.odometricPose());
    return world.odometricPose();
}

bool pathBlocked(const TPlannedPath& path, const std::vector<TPoint2D>& sensed, double v,
                 const TRobotOptions& robot, double margin, double lateralMargin,
                 double noiseTolerance) {
    const double reach =
        robot.radius + stoppingDistance(v, robot.t_delay, robot.decel) + margin;
    const double halfW = robot.radius + lateralMargin;
    const auto& pts = path.points;
    if (pts.size() < 2)
        return false;
    // only what lies ahead along the path and what the path comes nearer
    // to blocks it: a door post the robot is passing (beside it, or already
    // at its closest) cannot be stopped for, only steered away from
    const size_t a = std::min<size_t>(pts.size() - 1, 3);
    const double dx = pts[a].x - pts[0].x, dy = pts[a].y - pts[0].y;
    double along = 0;
    for (size_t k = 1; k < pts.size(); k++) {
        along += std::hypot(pts[k].x - pts[k - 1].x, pts[k].y - pts[k - 1].y);
        if (along > reach)
            break;
        for (const auto& q : sensed)
            if ((q.x - pts[0].x) * dx + (q.y - pts[0].y) * dy > 0) {
                const double dk = std::hypot(q.x - pts[k].x, q.y - pts[k].y);
                if (dk < halfW &&
                    dk < std::hypot(q.x - pts[0].x, q.y - pts[0].y) - noiseTolerance)
                    return true;
            }
    }
    return false;
}

TArrival judgeArrival(const mrpt::math::TPoint2D& destination,
                      const mrpt::math::TPose2D& truePose,
                      const mrpt::math::TPose2D& believedPose, double tolerance,
                      double nearestPossible) {
    TArrival a;
    a.trueError = std::hypot(destination.x - truePose.x, destination.y - truePose.y);
    a.beliefError = std::hypot(believedPose.x - truePose.x, believedPose.y - truePose.y);
    a.believedDistance =
        std::hypot(destination.x - believedPose.x, destination.y - believedPose.y);
    a.allowed = std::max(tolerance, std::max(0.0, nearestPossible) + tolerance / 2);
    a.reached = a.trueError < a.allowed;
    // the belief's error at least the miss: it accounts for the miss (always
    // so when the belief was within `allowed`: trueError <= believedDistance
    // + beliefError)
    a.status = a.reached                                  ? "reached"
               : a.beliefError >= a.trueError - a.allowed ? "localization_error"
                                                          : "fell_short";
    return a;
}

namespace {
/** Pure pursuit along the path at speed v; v = 0 (or a sharp turn) turns in
 * place towards the path, so that the robot looks where it will go.
 * Beyond plain pure pursuit: the look-ahead point is pulled back along the
 * path until the straight line to it keeps the clearance the path keeps
 * there (on a door post's corner the chord would cut past the slowest
 * speed's 5 cm margin).
 * And no faster than the arc to the look-ahead point can be turned at maxW
 * (regulated pure pursuit): at 1.1 m/s and 90 deg/s the tightest arc has a
 * 0.70 m radius, and a bend the path takes tighter was driven wide of the
 * path by more than the fastest speed's 0.30 m margin, then braked from
 * 1 m/s into the door post beside it. */
std::pair<double, double> follow(const TPlannedPath& path, const TPlanningField& field,
                                 const TPose2D& p, double v, double maxW, double radius) {
    const auto& pts = path.points;
    if (pts.size() < 2)
        return {0.0, 0.0};
    const double L = std::max(0.3, 0.5 * v + 0.15);
    const size_t t = lookaheadPoint(path, field, {p.x, p.y}, L).ahead;
    const double alpha =
        mrpt::math::wrapToPi(std::atan2(pts[t].y - p.y, pts[t].x - p.x) - p.phi);
    // where the robot has less than 10 cm to spare, an arc that starts off
    // the chord can touch what the chord passes: it turns on the spot first
    const double maxAlpha = field.clearanceAt(p.x, p.y) < radius + 0.1 ? 0.15 : 1.0;
    if (v <= 0 || std::abs(alpha) > maxAlpha)
        return {0.0, std::clamp(1.5 * alpha, -maxW, maxW)};
    const double dist = std::max(std::hypot(pts[t].x - p.x, pts[t].y - p.y), 1e-3);
    const double kappa = 2 * std::sin(alpha) / dist;  // the arc to the look-ahead point
    if (std::abs(kappa) * v > maxW)
        v = maxW / std::abs(kappa);
    return {v, std::clamp(kappa * v, -maxW, maxW)};
}

const double kInf = std::numeric_limits<double>::infinity();
const TPoint2D kNoNearest(kInf, kInf);  // no point nearest the destination
}  // namespace

/** One mode's run on the closed loop: runMode()'s state. Each cycle senses,
 * maps and decides (the pipeline), judges arrivals and records
 * (onCycle()); each sub-step follows the cycle's path (onSubStep()). */
struct CExplorer::TModeRun : public sim::CClosedLoop {
    TModeRun(CExplorer& explorer, const TOptions& lo, int fixedIdx,
             const std::function<void(double)>& progressFn, const TPose2D& start,
             const TPose2D& ego0);
    bool onCycle(int cycle) override;
    void onSubStep(int, int) override;
    void onStepped(int, int, const TPose2D&) override;
    void onCycleEnd(int) override;
    /** The destinations the belief `ego` arrived at, judged; false when
     * none is left. */
    bool judgeArrivals(const TPose2D& ego);
    /** The speed driven this cycle: the decision's, held, slowed for the
     * destination or braked by the stopping rule (rec.reason says why). */
    void chooseSpeed(TCycleRecord& rec, const sim::CSimWorld::TScans& scans,
                     const TPose2D& ego);
    /** The not-approaching and unreachable alarms. */
    void watchApproach(const TPose2D& ego);
    /** On to the next destination, this one `status`. */
    void nextDestination(const char* status);
    /** The belief in the world frame: world = start + (ego0^-1 + ego), as
     * the destinations were placed in the ego frame. */
    TPose2D believedInWorld(const TPose2D& ego) const {
        return (s0 + (mrpt::poses::CPose2D(ego) - e0)).asTPose();
    }

    CExplorer& ex;
    const int fixedIndex;
    const std::function<void(double)>& progress;
    TModeResult r;
    // mapping, fusion, planning field and the controller, one cycle at a time
    CAdaptiveSpeedPipeline pipeline;
    // destinations in the ego frame: ego = ego0 + (start^-1 + world point)
    const mrpt::poses::CPose2D e0, s0;
    std::vector<TPoint2D> goalsWorld, goalsEgo;
    // how near the robot may truly come to each destination: 0 in the open,
    // more where it lies nearer an obstacle than the robot's radius and the
    // slowest speed's margin (judgeArrival())
    std::vector<double> nearestPossible;
    std::optional<TPoint2D> previousTarget;  // temporary, of this destination
    // the point nearest this destination; none: one at infinity, never arrived at
    // (not a std::optional: gcc 12 warned it might be read uninitialized)
    TPoint2D nearestTarget = kNoNearest;
    double bestToGoal = std::numeric_limits<double>::infinity(), bestToGoalTime = 0;
    double unreachableSince = -1;
    size_t dest = 0;
    int lastSpeedIndex = -2;
    double lookAroundW = 0, lookAroundEnd = 0, noiseTolerance = 0;
    // the cycle's decision, driven over its sub-steps
    TSpeedDecision d;
    double v = 0, vc = 0;
    int vIndex = -1;
    bool lookingAround = false;
};

CExplorer::TModeRun::TModeRun(CExplorer& explorer, const TOptions& lo, int fixedIdx,
                              const std::function<void(double)>& progressFn,
                              const TPose2D& start, const TPose2D& ego0)
    : sim::CClosedLoop(explorer.world, lo),
      ex(explorer),
      fixedIndex(fixedIdx),
      progress(progressFn),
      pipeline(explorer.pipelineParams(), ego0),
      e0(ego0),
      s0(start) {
    const auto& explore = ex.explore;
    const auto& speed = ex.speed;
    r.fixedIndex = fixedIndex;
    if (fixedIndex < 0) {
        r.name = "adaptive";
    } else {
        r.name = "fixed_" + numberText(speed.speeds[size_t(fixedIndex)]);
    }
    for (size_t k = 0; k + 1 < explore.destinations.size(); k += 2) {
        goalsWorld.emplace_back(explore.destinations[k], explore.destinations[k + 1]);
        const mrpt::poses::CPoint2D local =
            mrpt::poses::CPoint2D(goalsWorld.back().x, goalsWorld.back().y) - s0;
        const auto ge = e0 + local;
        goalsEgo.emplace_back(ge.x(), ge.y());
        nearestPossible.push_back(std::max(
            0.0, world.robot.radius + speed.margins.back() -
                     world.pointClearance(goalsWorld.back().x, goalsWorld.back().y)));
    }
    r.destinationStatus.assign(goalsWorld.size(), "not_reached");
    r.destinationError.assign(goalsWorld.size(),
                              std::numeric_limits<double>::quiet_NaN());
    r.destinationBeliefError = r.destinationError;
    r.timeAtSpeed.assign(speed.speeds.size(), 0.0);
    lookAroundW = 0.8 * world.robot.max_w_deg * M_PI / 180;
    // one turn, plus a second for the turn-rate ramp
    lookAroundEnd = 2 * M_PI / lookAroundW + 1.0;
    // two standard deviations of the noisier range sensor, 1 cm at least
    noiseTolerance = std::max(0.01, 2 * world.laser.options.noise_std);
    if (world.range2.options.enabled)
        noiseTolerance = std::max(noiseTolerance, 2 * world.range2.options.noise_std);
}

void CExplorer::TModeRun::nextDestination(const char* status) {
    r.destinationStatus[dest] = status;
    dest++;
    previousTarget.reset();
    nearestTarget = kNoNearest;
    unreachableSince = -1;
    bestToGoal = std::numeric_limits<double>::infinity();
    bestToGoalTime = world.time();
}

bool CExplorer::TModeRun::judgeArrivals(const TPose2D& ego) {
    const auto& explore = ex.explore;
    // arrived, as the robot believes: within arrival_radius, or (a
    // destination nearer an obstacle than the robot may come) at the
    // point nearest it. It halts and goes on: it cannot know the truth.
    auto arrived = [&] {
        return std::hypot(goalsEgo[dest].x - ego.x, goalsEgo[dest].y - ego.y) <
                   explore.arrival_radius ||
               std::hypot(nearestTarget.x - ego.x, nearestTarget.y - ego.y) <
                   std::min(explore.arrival_radius, explore.goal_tolerance / 2);
    };
    // reached is judged on the true pose; a belief that arrived where
    // the truth is not within goal_tolerance is a localization error
    while (dest < goalsEgo.size() && arrived()) {
        const TArrival a =
            judgeArrival(goalsWorld[dest], world.truePose(), believedInWorld(ego),
                         explore.goal_tolerance, nearestPossible[dest]);
        r.destinationError[dest] = a.trueError;
        r.destinationBeliefError[dest] = a.beliefError;
        nextDestination(a.status);
    }
    return dest < goalsEgo.size();
}

bool CExplorer::TModeRun::onCycle(int cycle) {
    const auto& explore = ex.explore;
    if (!(world.time() < explore.duration_max && dest < goalsEgo.size()))
        return false;
    const auto scans = world.sense();
    const auto t0 = std::chrono::steady_clock::now();
    // the robot's localization (beyond the paper): this scan aligned to
    // the map built from the earlier ones, odometry as the prior
    if (ex.m_localizer)
        ex.m_localizer->update(world.odometricPose(), scans.laser.get());
    const double localizationMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
            .count();
    const TPose2D ego = ex.egoPose();
    pipeline.update(ego, scans.laser.get(), scans.range2.get());
    const TPlanningField& field = pipeline.field();
    if (!judgeArrivals(ego))
        return false;
    // Beyond the paper: first a turn on the spot, so that the laser (180
    // deg, ahead of the centre) has seen all around before the fused map
    // is asked for free space beside and behind the robot.
    lookingAround = explore.look_around && world.time() < lookAroundEnd;
    d = lookingAround ? TSpeedDecision{}
                      : pipeline.decide(ego, goalsEgo[dest], fixedIndex, previousTarget);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
            .count();
    TCycleRecord rec;
    rec.cycle = cycle;
    rec.t = world.time();
    rec.truePose = world.truePose();
    rec.egoPose = ego;
    rec.distance = r.distance;
    rec.chosen = d.speed;
    rec.reason = lookingAround ? "look_around" : reasonName(d.reason);
    rec.dUndecided = d.dUndecided;
    for (const auto& p : d.perSpeed)
        rec.costToGo.push_back(p.costToGo);
    rec.destination = int(dest);
    rec.temporaryTarget = d.temporaryTarget;
    if (!lookingAround) {
        if (d.nearestToGoal)
            nearestTarget = d.target;
        else
            nearestTarget = kNoNearest;
        if (d.temporaryTarget && d.reason != TSpeedReason::Unreachable)
            previousTarget = d.target;
        else
            previousTarget.reset();
    }
    rec.marginBroken = d.marginBroken;
    rec.computeMs = ms;
    rec.localizationMs = localizationMs;
    chooseSpeed(rec, scans, ego);
    rec.commanded = v;
    watchApproach(ego);
    r.marginBrokenCycles += d.marginBroken ? 1 : 0;
    r.cycles.push_back(rec);
    r.observations.push_back(rec.truePose);
    if (fixedIndex < 0 && (d.speedIndex != lastSpeedIndex || cycle < 3) &&
        int(r.snapshots.size()) < explore.max_snapshots) {
        TSnapshot s;
        s.cycle = cycle;
        s.field = field;
        s.decision = d;
        s.egoPose = ego;
        r.snapshots.push_back(std::move(s));
    }
    lastSpeedIndex = d.speedIndex;
    return true;
}

void CExplorer::TModeRun::chooseSpeed(TCycleRecord& rec,
                                      const sim::CSimWorld::TScans& scans,
                                      const TPose2D& ego) {
    const auto& speed = ex.speed;
    const auto& stopRule = ex.stopRule;
    // the stopping rule: sensed obstacles within the stopping distance
    v = d.speed;
    vIndex = d.speedIndex;
    // Beyond the paper: a robot held by the undecided rule has, after N
    // cycles in place, observed the region N times; what is still
    // undecided then (a gap in a wall seen edge-on) will not be decided
    // from here, so it creeps on at the slowest speed.
    if (pipeline.heldLongEnough(!lookingAround && d.reason == TSpeedReason::Undecided &&
                                d.speed == 0 && d.path.points.size() > 1)) {
        vIndex = int(speed.speeds.size()) - 1;
        v = speed.speeds.back();
    }
    // Beyond the paper: at a destination the robot stops, so no speed
    // whose stopping distance exceeds the path left to it
    if (!lookingAround && !d.temporaryTarget && d.speedIndex >= 0) {
        const double left = d.path.length;
        while (vIndex >= 0 && vIndex + 1 < int(speed.speeds.size()) &&
               stoppingDistance(v, world.robot.t_delay, world.robot.decel) > left) {
            vIndex++;
            v = speed.speeds[size_t(vIndex)];
            rec.reason = "goal";
        }
    }
    // the sensed points in the ego frame, when the stopping rule will look
    std::vector<TPoint2D> sensed;
    for (const auto& sc : {scans.laser, scans.range2})
        if (sc && stopRule.options.enabled && v > 0)
            for (const auto& q : mapping::scanToRobotFrame(*sc))
                sensed.emplace_back(
                    ego.x + std::cos(ego.phi) * q.x - std::sin(ego.phi) * q.y,
                    ego.y + std::sin(ego.phi) * q.x + std::cos(ego.phi) * q.y);
    // a robot still faster than speedV (braking from a faster candidate)
    // stops from the speed it drives, not from the one it is told
    const double driven = world.speed();
    auto blocked = [&](double speedV) {
        return stopRule.options.enabled && speedV > 0 &&
               pathBlocked(d.path, sensed, std::max(speedV, driven), world.robot,
                           stopRule.options.margin, stopRule.options.lateral_margin,
                           noiseTolerance);
    };
    if (blocked(v)) {
        v = 0;
        vIndex = -1;
        if (fixedIndex < 0)
            for (size_t k = size_t(std::max(0, d.speedIndex)) + 1;
                 k < speed.speeds.size(); k++)
                if (!blocked(speed.speeds[k])) {
                    v = speed.speeds[k];
                    vIndex = int(k);
                    break;
                }
        rec.reason = "obstacle";
    }
}

void CExplorer::TModeRun::watchApproach(const TPose2D& ego) {
    const auto& explore = ex.explore;
    // the not-approaching alarm
    const double toGoal = std::hypot(goalsEgo[dest].x - ego.x, goalsEgo[dest].y - ego.y);
    if (toGoal < bestToGoal - 0.5) {
        bestToGoal = toGoal;
        bestToGoalTime = world.time();
    }
    if (explore.not_approaching_timeout > 0 &&
        world.time() - bestToGoalTime > explore.not_approaching_timeout) {
        nextDestination("unreachable");
    } else if (d.reason == TSpeedReason::Unreachable && !lookingAround) {
        if (unreachableSince < 0)
            unreachableSince = world.time();
        else if (world.time() - unreachableSince >= explore.unreachable_after)
            nextDestination("unreachable");
    } else {
        unreachableSince = -1;
    }
}

// drive the cycle
void CExplorer::TModeRun::onSubStep(int, int) {
    double wc = 0;
    std::tie(vc, wc) =
        lookingAround ? std::pair<double, double>(0.0, lookAroundW)
                      : follow(d.path, pipeline.field(), ex.egoPose(), v,
                               world.robot.max_w_deg * M_PI / 180, world.robot.radius);
    world.command(vc, wc);
}

void CExplorer::TModeRun::onStepped(int, int, const TPose2D&) {
    if (vc <= 0)
        r.timeStopped += options.sim_dt;
    else if (vIndex >= 0)
        r.timeAtSpeed[size_t(vIndex)] += options.sim_dt;
}

void CExplorer::TModeRun::onCycleEnd(int) {
    r.distance = travelled();
    if (progress)
        progress(world.time());
}

TModeResult CExplorer::runMode(int fixedIndex,
                               const std::function<void(double)>& progress) {
    const TPose2D start(explore.start[0], explore.start[1],
                        explore.start[2] * M_PI / 180);
    world.reset(start, explore.seed);
    m_localizer.reset();
    if (explore.ego_motion == "scan_matching")
        m_localizer.emplace(scanMatch);
    const double T = speed.cycle_time;
    const TPose2D ego0 = egoPose();
    const int steps = std::max(1, int(std::lround(T / explore.sim_dt)));
    sim::CClosedLoop::TOptions lo;
    lo.sim_dt = T / steps;
    lo.steps_per_cycle = steps;
    TModeRun m(*this, lo, fixedIndex, progress, start, ego0);
    m.run();
    TModeResult& r = m.r;
    r.time = world.time();
    r.collisions = m.safety.collisions();
    r.collisionsStatic = m.safety.collisionsStatic();
    r.nearMisses = m.safety.nearMisses();
    r.minClearance = m.safety.minGapStatic();
    if (m_localizer) {
        r.localization = m_localizer->stats();
        r.localizationMapPoints = m_localizer->map().size();
    }
    return std::move(m.r);
}
}  // namespace risknav::speed
