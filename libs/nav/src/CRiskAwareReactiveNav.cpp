#include <risknav/common/CRangeSensingRobot.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>

#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/nav/reactive/CLogFileRecord.h>
#include <mrpt/nav/tpspace/CParameterizedTrajectoryGenerator.h>

#include <mrpt/math/TSegment2D.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

// The host: MRPT's engine and its cycle, the limiters in it, the global
// planner in front of it. Its config (load, save, checks):
// CRiskAwareReactiveNav_config.cpp; its own turns: CTurnSupervisor; its own
// driving: CPlanFollower.

using namespace risknav::common;

namespace risknav::nav {
CRiskAwareReactiveNav::CRiskAwareReactiveNav(mrpt::nav::CRobot2NavInterface& r,
                                             bool console, bool logFile,
                                             const std::string& logDir)
    : mrpt::nav::CReactiveNavigationSystem(r, console, logFile, logDir) {
    registerAllClasses_nav();
}

void CRiskAwareReactiveNav::syncOptions() {
    const auto& o = riskOptions;
    m_turns.options = {o.turn_in_place_deg, o.turn_rate_deg, o.start_turn_deg,
                       o.unstick_time, o.unstick_heading_deg};
    m_follower.options = {o.plan_follow_after,    o.plan_follow_speed,
                          o.plan_follow_distance, o.plan_follow_margin,
                          o.final_approach_speed, o.turn_rate_deg};
}

void CRiskAwareReactiveNav::navigateWaypoints(
    const mrpt::nav::TWaypointSequence& request) {
    mrpt::nav::CWaypointsNavigator::navigateWaypoints(request);
    m_requestPending = !request.waypoints.empty();
    m_planFailure.reset();  // a new navigation, not the last one's no-way
}

std::optional<CRiskAwareReactiveNav::TCurrentTarget>
CRiskAwareReactiveNav::currentTarget() const {
    return currentTarget(getWaypointNavStatus());
}

std::optional<CRiskAwareReactiveNav::TCurrentTarget> CRiskAwareReactiveNav::currentTarget(
    const mrpt::nav::TWaypointStatusSequence& st) const {
    if (getCurrentState() != NAVIGATING && !m_requestPending)
        return std::nullopt;
    for (size_t i = 0; i < st.waypoints.size(); i++)
        if (const auto& w = st.waypoints[i]; !w.reached)
            return TCurrentTarget{w.target, w.allowed_distance,
                                  i + 1 == st.waypoints.size()};
    if (m_navigationParams)
        return TCurrentTarget{
            mrpt::math::TPoint2D(m_navigationParams->target.target_coords.x,
                                 m_navigationParams->target.target_coords.y),
            m_navigationParams->target.targetAllowedDistance};
    return std::nullopt;
}

void CRiskAwareReactiveNav::navigationStep() {
    syncOptions();
    std::optional<mrpt::math::TPoint2D> target;
    double targetAllowed = 0;
    bool lastTarget = false;
    std::optional<mrpt::math::TPoint2D> lastStepPose;
    if (riskOptions.turn_in_place_deg > 0 || riskOptions.unstick_time > 0 ||
        riskOptions.start_turn_deg > 0 || riskOptions.final_approach_speed > 0 ||
        m_planner) {
        const auto st = getWaypointNavStatus();  // one copy for both
        if (const auto ct = currentTarget(st)) {
            target = ct->point;
            targetAllowed = ct->allowedDistance;
            lastTarget = ct->last;
            if (st.last_robot_pose.x != mrpt::nav::TWaypoint::INVALID_NUM)
                lastStepPose =
                    mrpt::math::TPoint2D(st.last_robot_pose.x, st.last_robot_pose.y);
        }
    }
    if (target) {
        mrpt::math::TPose2D pose, odo;
        mrpt::math::TTwist2D vel;
        mrpt::system::TTimeStamp ts;
        std::string frame;
        // MRPT's CWaypointsNavigator counts a waypoint as reached when the
        // robot's move since its last step (the segment from that step's pose
        // to now) passes within allowed_distance of it, and marks it so in
        // its next step. Such a waypoint is not turned to: e.g. a route's
        // first waypoint at the start (its bearing is atan2 of micrometres,
        // noise) or one just passed, now behind the robot.
        auto reachedByMrpt = [&](const mrpt::math::TPose2D& p) {
            const mrpt::math::TPoint2D now(p.x, p.y);
            const mrpt::math::TSegment2D move(now, lastStepPose.value_or(now));
            return move.distance(*target) < targetAllowed;
        };
        if (m_robot.getCurrentPoseAndSpeeds(pose, vel, ts, odo, frame) &&
            !reachedByMrpt(pose)) {
            if (m_planner && !updatePlanner(pose, *target))
                return;  // no way: stopped
            const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
            // the robot driven by the navigator itself, not MRPT: along the
            // plan (plan_follow_after), or to the route's end inside MRPT's
            // shape (final_approach_speed)
            const CPlanFollower::TBody body{shapeRadius(), robot.radius};
            const auto sensed = [&] { return sensedAround(pose, now); };
            std::optional<CPlanFollower::TDrive> own;
            if (m_planner)
                own = m_follower.followPlan(pose, now, *m_planner, body, targetAllowed,
                                            lastTarget, sensed);
            if (!own && lastTarget)
                own =
                    m_follower.finalApproach(pose, *target, targetAllowed, body, sensed);
            if (own) {
                sendOwnCommand(own->cmd, own->mode, own->reason);
                return;
            }
            // or turned in place (CTurnSupervisor)
            CTurnSupervisor::TInput in;
            in.pose = pose;
            in.speed = std::hypot(vel.vx, vel.vy);
            in.target = *target;
            in.now = now;
            in.guidePoint = [&] { return guidePoint(pose, *target); };
            in.pointsNearShape = [&] {
                return CTurnSupervisor::pointsNearShape(m_WS_Obstacles, shapeRadius());
            };
            if (const auto turn = m_turns.step(in)) {
                mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
                cmd.lin_vel = 0;
                cmd.ang_vel = turn->angVel;
                m_robot.changeSpeeds(cmd);
                m_last = {};
                m_last.turning = true;
                m_last.unsticking = turn->unsticking;
                m_last.reason = turn->reason;
                return;
            }
        }
    }
    m_turns.endTurn();
    m_last = {};  // set by generate_vel_cmd() when MRPT sends a new command
    m_observeDue = !m_limiters.empty();
    try {
        mrpt::nav::CReactiveNavigationSystem::navigationStep();
    } catch (...) {
        m_observeDue = false;
        finishObserved(true);
        throw;
    }
    m_observeDue = false;
    finishObserved(false);
    m_requestPending = false;  // MRPT's step took it
    if (m_planner && target) {
        // what MRPT sensed this step (robot frame of its pose then)
        const auto& xs = m_WS_Obstacles.getPointsBufferRef_x();
        const auto& ys = m_WS_Obstacles.getPointsBufferRef_y();
        std::vector<mrpt::math::TPoint2D> pts(xs.size());
        for (size_t k = 0; k < xs.size(); k++)
            pts[k] = mrpt::math::TPoint2D(xs[k], ys[k]);
        m_planner->addSensed(m_curPoseVel.pose, pts,
                             mrpt::Clock::toDouble(mrpt::Clock::now()));
    }
}

bool CRiskAwareReactiveNav::updatePlanner(const mrpt::math::TPose2D& pose,
                                          const mrpt::math::TPoint2D& target) {
    const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
    const auto ev = m_planner->update(pose, target, now);
    if (ev)  // a new plan: its own headway
        m_planBest = std::numeric_limits<double>::infinity();
    const auto& plan = m_planner->current();
    if (!plan.found) {
        m_planFailure = plan;
        m_follower.cancel();
        doEmergencyStop("[CGlobalPlanner] no way to the target: " + plan.reason);
        return false;
    }
    // MRPT's "not approaching the target" alarm on the way left along the
    // plan: a detour round a wall leads away from the target for a while
    const double left = m_planner->remainingLength(pose);
    if (left < m_planBest - 0.1) {
        m_planBest = left;
        m_badNavAlarm_lastMinDistTime = mrpt::Clock::now();
    }
    m_follower.planUpdated(ev.has_value(), ev && ev->why == "new_target", left, now);
    return true;
}

void CRiskAwareReactiveNav::sendOwnCommand(const TFollowCommand& cmd, const char* limiter,
                                           const std::string& reason) {
    mrpt::kinematics::CVehicleVelCmd_DiffDriven vc;
    vc.lin_vel = cmd.v;
    vc.ang_vel = cmd.w;
    m_robot.changeSpeeds(vc);
    m_last = {};
    m_last.limiter = limiter;
    m_last.desired = m_last.limit = cmd.v;
    m_last.reason = reason;
}

double CRiskAwareReactiveNav::shapeRadius() const {
    double r = 0;
    for (const auto& v : m_robotShape)
        r = std::max(r, std::hypot(v.x, v.y));
    return m_robotShape.empty() ? m_robotShapeCircularRadius : r;
}

std::vector<mrpt::math::TPoint2D> CRiskAwareReactiveNav::senseNow(
    const mrpt::math::TPose2D& pose, double now) {
    // MRPT's last scans are a cycle old, and it does not sense while the
    // navigator drives: the robot's own, robot frame now
    mrpt::maps::CSimplePointsMap sensed;
    mrpt::system::TTimeStamp ts;
    std::vector<mrpt::math::TPoint2D> pts;
    if (m_robot.senseObstacles(sensed, ts)) {
        const auto& xs = sensed.getPointsBufferRef_x();
        const auto& ys = sensed.getPointsBufferRef_y();
        pts.reserve(xs.size());
        for (size_t k = 0; k < xs.size(); k++)
            pts.emplace_back(xs[k], ys[k]);
        if (m_planner)
            m_planner->addSensed(pose, pts, now);
    }
    return pts;
}

std::vector<mrpt::math::TPoint2D> CRiskAwareReactiveNav::sensedAround(
    const mrpt::math::TPose2D& pose, double now) {
    auto pts = senseNow(pose, now);
    // and what it sensed before beside and behind it (its laser looks
    // ahead; an arc swings the shape's side round a post seen earlier)
    if (m_planner) {
        const auto before = m_planner->sensedNear(pose, shapeRadius() + 0.5);
        pts.insert(pts.end(), before.begin(), before.end());
    }
    return pts;
}

void CRiskAwareReactiveNav::STEP3_WSpaceToTPSpace(
    const size_t ptg_idx, std::vector<double>& out_TPObstacles,
    mrpt::nav::ClearanceDiagram& out_clearance,
    const mrpt::math::TPose2D& rel_pose_PTG_origin_wrt_sense, const bool eval_clearance) {
    observeNow(false);
    mrpt::nav::CReactiveNavigationSystem::STEP3_WSpaceToTPSpace(
        ptg_idx, out_TPObstacles, out_clearance, rel_pose_PTG_origin_wrt_sense,
        eval_clearance);
}

void CRiskAwareReactiveNav::observeNow(bool beforeSensing) {
    if (!m_observeDue)
        return;
    if (beforeSensing) {
        // A robot that senses ahead (CRangeSensingRobot, e.g. a risknav
        // world) senses now the scans MRPT's sensing then takes, so the
        // limiters start ~0.2-0.3 ms of MRPT's step earlier (its sensing and
        // its work up to the first PTG); another robot's scans exist only
        // once MRPT sensed: its limiters observe in STEP3_WSpaceToTPSpace().
        auto* r = dynamic_cast<CRangeSensingRobot*>(&m_robot);
        if (!r)
            return;
        r->senseAhead();
    }
    m_observeDue = false;
    TSpeedLimitInput in = limiterInput(nullptr, 0.0);
    if (beforeSensing)
        in.obstacles = nullptr;  // MRPT's point map is still the last step's
    for (const auto& l : m_limiters)
        l->observe(in);
}

void CRiskAwareReactiveNav::finishObserved(bool quiet) {
    for (const auto& l : m_limiters) {
        try {
            l->finishObserved();
        } catch (const std::exception& e) {
            if (!quiet)
                doEmergencyStop(std::string("[CRiskAwareReactiveNav] ") + e.what());
        }
    }
}

std::optional<mrpt::math::TPoint2D> CRiskAwareReactiveNav::guidePoint(
    const mrpt::math::TPose2D& pose, const mrpt::math::TPoint2D& target) const {
    if (m_planner) {
        const auto pt = m_planner->currentTarget();
        if (pt && std::hypot(pt->x - target.x, pt->y - target.y) < 1e-9 &&
            std::hypot(target.x - pose.x, target.y - pose.y) >
                m_planner->options.lookahead)
            if (auto g = m_planner->guidePoint(pose))
                return g;
    }
    const double L = riskOptions.guide_lookahead;
    if (!(L > 0) || m_turns.guidePaused() ||
        std::hypot(target.x - pose.x, target.y - pose.y) <= L)
        return std::nullopt;
    for (const auto& l : m_limiters)
        if (auto g = l->guidePoint(pose, L))
            return g;
    return std::nullopt;
}

void CRiskAwareReactiveNav::performNavigationStep() {
    std::optional<mrpt::math::TPoint2D> guide;
    if (m_navigationParams && !m_navigationParams->target.targetIsRelative) {
        const auto& t = m_navigationParams->target.target_coords;
        guide = guidePoint(m_curPoseVel.pose, mrpt::math::TPoint2D(t.x, t.y));
    }
    if (!guide) {
        observeNow(true);
        mrpt::nav::CReactiveNavigationSystem::performNavigationStep();
        return;
    }
    // MRPT aims at the guide point for this step only (as its one target:
    // CWaypointsNavigator's multiple_targets, the waypoints it may head to,
    // are set aside too): its waypoint bookkeeping (reached, the timeout
    // approaching it) ran before, on the waypoint; no slow-down approaching
    // the guide point (relative speed 1)
    auto* wp = dynamic_cast<TNavigationParamsWaypoints*>(m_navigationParams.get());
    const auto saved = m_navigationParams->target;
    std::vector<TargetInfo> savedMultiple;
    m_realTarget = mrpt::math::TPoint2D(saved.target_coords.x, saved.target_coords.y);
    m_navigationParams->target.target_coords.x = guide->x;
    m_navigationParams->target.target_coords.y = guide->y;
    m_navigationParams->target.targetDesiredRelSpeed = 1.0;
    if (wp)
        savedMultiple.swap(wp->multiple_targets);
    auto restore = [&] {
        m_realTarget.reset();
        if (!m_navigationParams)
            return;
        m_navigationParams->target = saved;
        if (auto* w = dynamic_cast<TNavigationParamsWaypoints*>(m_navigationParams.get()))
            w->multiple_targets = savedMultiple;
    };
    try {
        observeNow(true);  // the waypoint as the target (m_realTarget)
        mrpt::nav::CReactiveNavigationSystem::performNavigationStep();
    } catch (...) {
        restore();
        throw;
    }
    restore();
}

TSpeedLimitInput CRiskAwareReactiveNav::limiterInput(
    const mrpt::nav::TCandidateMovementPTG* movement, double desired) const {
    TSpeedLimitInput in;
    in.robot = &robot;
    in.pose = m_curPoseVel.pose;
    in.desiredSpeed = desired;
    in.obstacles = &m_WS_Obstacles;
    in.time = mrpt::Clock::toDouble(mrpt::Clock::now());
    if (m_realTarget)
        in.target = m_realTarget;  // the waypoint, not the guide point MRPT aims at
    else if (m_navigationParams)
        in.target = mrpt::math::TPoint2D(m_navigationParams->target.target_coords.x,
                                         m_navigationParams->target.target_coords.y);
    // MRPT's chosen trajectory, sampled every ~5 cm over the stopping
    // distance at the desired speed and a margin: what the limiters judge.
    if (auto* ptg = movement ? movement->PTG : nullptr) {
        const uint16_t k = ptg->alpha2index(movement->direction);
        const size_t n = ptg->getPathStepCount(k);
        const double reach =
            stoppingDistance(desired, robot.t_delay, robot.decel) + robot.radius + 1.0;
        double last = -1;
        for (size_t i = 0; i < n; i++) {
            const double d = ptg->getPathDist(k, uint32_t(i));
            if (i + 1 < n && d - last < 0.05)
                continue;
            in.path.push_back(ptg->getPathPose(k, uint32_t(i)));
            in.pathDistance.push_back(d);
            last = d;
            if (d > reach)
                break;
        }
    }
    // The raw scans (rays, not only their end points) when the robot gives
    // them: the adaptive limiter maps free space along them.
    if (const auto* r = dynamic_cast<const CRangeSensingRobot*>(&m_robot)) {
        in.scan = r->lastScan();
        in.scan2 = r->lastScan2();
    }
    return in;
}

double CRiskAwareReactiveNav::generate_vel_cmd(
    const mrpt::nav::TCandidateMovementPTG& in_movement,
    mrpt::kinematics::CVehicleVelCmd::Ptr& new_vel_cmd) {
    const double scale =
        mrpt::nav::CReactiveNavigationSystem::generate_vel_cmd(in_movement, new_vel_cmd);
    m_last = {};
    if (!new_vel_cmd || new_vel_cmd->getVelCmdLength() == 0)
        return scale;
    // Element 0 is the forward speed of MRPT's diff-drive and holonomic commands.
    const double desired = std::abs(new_vel_cmd->getVelCmdElement(0));
    m_last.desired = m_last.limit = desired;
    if (m_limiters.empty() || !(desired > 0))
        return scale;
    TSpeedLimitInput in = limiterInput(&in_movement, desired);
    for (size_t i = 0; i < m_limiters.size(); i++) {
        // Each limiter judges the speed the ones before it left (the
        // stopping distance of 0.2 m/s, not of MRPT's 1.1).
        in.desiredSpeed = m_last.limit;
        const TSpeedLimit l = m_limiters[i]->limit(in);
        if (l.maxSpeed < m_last.limit) {
            m_last.limit = l.maxSpeed;
            m_last.limiter = shortClassName(riskOptions.speed_limiters[i]);
            m_last.reason = l.reason;
        }
    }
    if (m_last.limit >= desired)
        return scale;
    const double s = std::max(0.0, m_last.limit / desired);
    auto* dd =
        dynamic_cast<mrpt::kinematics::CVehicleVelCmd_DiffDriven*>(new_vel_cmd.get());
    if (s == 0 && dd) {
        // Stopped: keep MRPT's turn, in place (a disc robot sweeps nothing
        // new), so that it can turn away from what stopped it; scaling the
        // turn too would hold it facing the obstacle for ever.
        dd->lin_vel = 0;
        return scale;
    }
    new_vel_cmd->cmdVel_scale(s);
    return scale * s;
}

void CRiskAwareReactiveNav::loggingGetWSObstaclesAndShape(
    mrpt::nav::CLogFileRecord& out) {
    mrpt::nav::CReactiveNavigationSystem::loggingGetWSObstaclesAndShape(out);
    out.values["speed_desired"] = m_last.desired;
    out.values["speed_limit"] = m_last.limit;
    out.additional_debug_msgs["speed_limiter"] =
        m_last.limiter.empty() ? "none" : m_last.limiter + ": " + m_last.reason;
    if (m_realTarget && m_navigationParams) {
        // MRPT's own record has the guide point as its target
        const auto& g = m_navigationParams->target.target_coords;
        out.values["guide_x"] = g.x;
        out.values["guide_y"] = g.y;
        out.additional_debug_msgs["guide"] =
            "aimed at (" + numberText(g.x) + ", " + numberText(g.y) +
            ") on the limiter's way to the waypoint (" + numberText(m_realTarget->x) +
            ", " + numberText(m_realTarget->y) + ")";
    }
}

}  // namespace risknav::nav
