#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CLayeredConfig.h>
#include <risknav/nav/CNullRobot.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/nav/engine_config_check.h>
#include <risknav/nav/escape_heading.h>
#include <risknav/nav/plan_follow.h>
#include <risknav/sim/CSimRobotInterface.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/maps/CPointCloudFilterByDistance.h>
#include <mrpt/nav/reactive/CLogFileRecord.h>
#include <mrpt/nav/tpspace/CPTG_DiffDrive_alpha.h>
#include <mrpt/nav/tpspace/CParameterizedTrajectoryGenerator.h>

#include <mrpt/math/TSegment2D.h>
#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

using namespace risknav::common;

namespace risknav::nav {
namespace {
const char* kSection = "CRiskAwareReactiveNav";
constexpr int kMaxUnstickTurns = 3;  // per target (see navigationStep())
/** [m] Points this far outside MRPT's robot shape count as at its edge
 * (pointsNearShape()): a laser's noise moves them in and out of it. */
constexpr double kShapeEdge = 0.03;

// A config that records the keys read from it (which of the keys MRPT's
// saveConfigFile() writes its loadConfigFile() reads back).
class CReadRecordingConfig : public mrpt::config::CConfigFileMemory {
  public:
    using mrpt::config::CConfigFileMemory::CConfigFileMemory;
    bool wasRead(const std::string& section, const std::string& key) const {
        return m_read.count(lowerCase(section + "\n" + key)) > 0;
    }

  protected:
    std::string readString(const std::string& section, const std::string& name,
                           const std::string& def,
                           bool failIfNotFound = false) const override {
        m_read.insert(lowerCase(section + "\n" + name));  // MRPT ignores case
        return mrpt::config::CConfigFileMemory::readString(section, name, def,
                                                           failIfNotFound);
    }

  private:
    mutable std::set<std::string> m_read;
};

}  // namespace

void CRiskAwareReactiveNav::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s) {
    const std::string list = readString(c, s, "speed_limiters", "");
    speed_limiters.clear();
    std::istringstream in(list);
    for (std::string name; in >> name;)
        speed_limiters.push_back(name);
    turn_in_place_deg = readDouble(c, s, "turn_in_place_deg", turn_in_place_deg);
    turn_rate_deg = readDouble(c, s, "turn_rate_deg", turn_rate_deg);
    start_turn_deg = readDouble(c, s, "start_turn_deg", start_turn_deg);
    unstick_time = readDouble(c, s, "unstick_time", unstick_time);
    unstick_heading_deg = readDouble(c, s, "unstick_heading_deg", unstick_heading_deg);
    guide_lookahead = readDouble(c, s, "guide_lookahead", guide_lookahead);
    plan_follow_after = readDouble(c, s, "plan_follow_after", plan_follow_after);
    plan_follow_speed = readDouble(c, s, "plan_follow_speed", plan_follow_speed);
    plan_follow_distance = readDouble(c, s, "plan_follow_distance", plan_follow_distance);
    plan_follow_margin = readDouble(c, s, "plan_follow_margin", plan_follow_margin);
    final_approach_speed = readDouble(c, s, "final_approach_speed", final_approach_speed);
}

void CRiskAwareReactiveNav::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                       const std::string& s) const {
    std::string list;
    for (const auto& n : speed_limiters)
        list += (list.empty() ? "" : " ") + n;
    writeKey(c, s, "speed_limiters", list);
    writeKey(c, s, "turn_in_place_deg", turn_in_place_deg);
    writeKey(c, s, "turn_rate_deg", turn_rate_deg);
    writeKey(c, s, "start_turn_deg", start_turn_deg);
    writeKey(c, s, "unstick_time", unstick_time);
    writeKey(c, s, "unstick_heading_deg", unstick_heading_deg);
    writeKey(c, s, "guide_lookahead", guide_lookahead);
    writeKey(c, s, "plan_follow_after", plan_follow_after);
    writeKey(c, s, "plan_follow_speed", plan_follow_speed);
    writeKey(c, s, "plan_follow_distance", plan_follow_distance);
    writeKey(c, s, "plan_follow_margin", plan_follow_margin);
    writeKey(c, s, "final_approach_speed", final_approach_speed);
}

void CRiskAwareReactiveNav::TOptions::validate() const {
    checkRule(speed_limiters.size() <= 16, kSection, "speed_limiters",
              std::to_string(speed_limiters.size()) + " names", "at most 16 limiters");
    // one instance per class: both would read one section, and a repeated
    // name is a typo, not a second limiter
    for (size_t i = 0; i < speed_limiters.size(); i++)
        for (size_t j = 0; j < i; j++)
            if (shortClassName(speed_limiters[i]) == shortClassName(speed_limiters[j])) {
                std::string list;
                for (const auto& n : speed_limiters)
                    list += (list.empty() ? "" : " ") + n;
                checkRule(false, kSection, "speed_limiters", list,
                          shortClassName(speed_limiters[i]) + " is listed twice");
            }
    checkKey(kSection, "turn_in_place_deg", turn_in_place_deg,
             TRange::closed(0, 180, "deg"));
    checkKey(kSection, "turn_rate_deg", turn_rate_deg, TRange::closed(1, 360, "deg/s"));
    checkKey(kSection, "start_turn_deg", start_turn_deg, TRange::closed(0, 180, "deg"));
    checkKey(kSection, "unstick_time", unstick_time, TRange::closed(0, 1e5, "s"));
    // below 2 s a robot driving 0.25 m/s (5 cm a 0.2 s cycle) would count as stuck
    checkRule(unstick_time == 0 || unstick_time >= 2, kSection, "unstick_time",
              numberText(unstick_time), "must be 0 (off) or at least 2 s");
    checkKey(kSection, "unstick_heading_deg", unstick_heading_deg,
             TRange::closed(1, 180, "deg"));
    checkKey(kSection, "guide_lookahead", guide_lookahead, TRange::closed(0, 20, "m"));
    checkKey(kSection, "plan_follow_after", plan_follow_after,
             TRange::closed(0, 1e5, "s"));
    checkRule(plan_follow_after == 0 || plan_follow_after >= 2, kSection,
              "plan_follow_after", numberText(plan_follow_after),
              "must be 0 (off) or at least 2 s");
    checkKey(kSection, "plan_follow_speed", plan_follow_speed,
             TRange::closed(0.02, 2, "m/s"));
    checkKey(kSection, "plan_follow_distance", plan_follow_distance,
             TRange::closed(0.1, 100, "m"));
    checkKey(kSection, "plan_follow_margin", plan_follow_margin,
             TRange::closed(0, 1, "m"));
    checkKey(kSection, "final_approach_speed", final_approach_speed,
             TRange::closed(0, 2, "m/s"));
}

CRiskAwareReactiveNav::CRiskAwareReactiveNav(mrpt::nav::CRobot2NavInterface& r,
                                             bool console, bool logFile,
                                             const std::string& logDir)
    : mrpt::nav::CReactiveNavigationSystem(r, console, logFile, logDir) {
    registerAllClasses_nav();
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
    const double limitDeg = riskOptions.turn_in_place_deg;
    std::optional<mrpt::math::TPoint2D> target;
    double targetAllowed = 0;
    bool lastTarget = false;
    std::optional<mrpt::math::TPoint2D> lastStepPose;
    if (limitDeg > 0 || riskOptions.unstick_time > 0 || riskOptions.start_turn_deg > 0 ||
        riskOptions.final_approach_speed > 0 || m_planner) {
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
            if (m_planner && followPlan(pose, targetAllowed, lastTarget))
                return;  // the robot follows the plan itself this cycle
            if (lastTarget && finalApproach(pose, *target, targetAllowed))
                return;  // the end, inside MRPT's shape: driven to
            // stuck: neither 5 cm nor 5 deg of motion for unstick_time (a
            // robot MRPT dithers by +-5 deg is not caught: turned to a
            // target behind a corner, MRPT's way round it was lost); a clock
            // gone back, or a new run, starts the watch again
            const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
            if (m_stillPose && now < m_stillSince)
                m_unstuck.reset(), m_guidePausedAt.reset();
            if (!m_stillPose || now < m_stillSince ||
                std::hypot(pose.x - m_stillPose->x, pose.y - m_stillPose->y) > 0.05 ||
                std::abs(mrpt::math::wrapToPi(pose.phi - m_stillPose->phi)) >
                    5 * M_PI / 180) {
                m_stillPose = pose;
                m_stillSince = now;
            }
            const double stillFor = now - m_stillSince;
            const bool stuck =
                riskOptions.unstick_time > 0 && stillFor >= riskOptions.unstick_time;
            // A robot stuck while MRPT is aimed at a guide point (e.g. frozen
            // at a slant in the entrance of a passage the way hugs) is aimed
            // straight at the waypoint again until it has moved 0.5 m or
            // has a new target (office seed 8: 45 s frozen between the desks).
            if (m_guidePausedAt &&
                (std::hypot(pose.x - m_guidePausedAt->first.x,
                            pose.y - m_guidePausedAt->first.y) > 0.5 ||
                 std::hypot(m_guidePausedAt->second.x - target->x,
                            m_guidePausedAt->second.y - target->y) > 1e-6))
                m_guidePausedAt.reset();
            if (stuck && !m_guidePausedAt && guidePoint(pose, *target))
                m_guidePausedAt = {mrpt::math::TPoint2D(pose.x, pose.y), *target};
            // turned to where MRPT is aimed: the guide point when a limiter
            // gives one (guide_lookahead), else the waypoint
            const mrpt::math::TPoint2D aim = guidePoint(pose, *target).value_or(*target);
            double bearing = mrpt::math::wrapToPi(
                std::atan2(aim.y - pose.y, aim.x - pose.x) - pose.phi);
            const double aimBearing = bearing;
            // an escape turn (below) turns to its own heading
            if (m_escapeHeading)
                bearing = mrpt::math::wrapToPi(*m_escapeHeading - pose.phi);
            double deg = std::abs(bearing) * 180 / M_PI;
            // At most kMaxUnstickTurns per target, counted again once the
            // robot got 0.5 m nearer to it than at the nearest turn: at a target
            // behind a wall, turning to it for ever would hide MRPT's own
            // verdict (its timeout approaching the target, way_seems_blocked)
            // and run to the end; one turn only left U-corridor robots
            // creeping for 100 s at a bend that a second turn gets them out of.
            const double dist = std::hypot(target->x - pose.x, target->y - pose.y);
            const bool sameTarget =
                m_unstuck && std::hypot(m_unstuck->target.x - target->x,
                                        m_unstuck->target.y - target->y) < 1e-6;
            if (!sameTarget)
                m_unstuck.reset();  // a new target (or the same one again later)
            const bool nearer = sameTarget && dist < m_unstuck->distance - 0.5;
            const bool mayUnstick =
                !sameTarget || nearer || m_unstuck->turns < kMaxUnstickTurns;
            const double unstickDeg = riskOptions.unstick_heading_deg;
            // the reference is the nearest the robot was at a turn: pushed
            // back and returning does not count as getting nearer
            auto countTurn = [&] {
                m_unstuck = sameTarget && !nearer
                                ? TUnstick{*target, std::min(dist, m_unstuck->distance),
                                           m_unstuck->turns + 1}
                                : TUnstick{*target, dist, 1};
            };
            const double startDeg = riskOptions.start_turn_deg;
            const bool standing = std::hypot(vel.vx, vel.vy) < 0.05;
            if (m_turning) {
                m_turning = deg > (m_unsticking     ? unstickDeg
                                   : m_startTurning ? startDeg
                                                    : limitDeg) /
                                      3;
                if (!m_turning)
                    m_escapeHeading.reset();
            } else if (limitDeg > 0 && deg > limitDeg) {
                m_turning = true, m_unsticking = false, m_startTurning = false;
            } else if (startDeg > 0 && deg > startDeg && standing && !m_escapeHeading) {
                m_turning = true, m_unsticking = false, m_startTurning = true;
            } else if (stuck && deg > unstickDeg && mayUnstick) {
                m_turning = true, m_unsticking = true;
                countTurn();
                m_unstickReason = "target " + numberText(std::round(deg)) +
                                  " deg off after " + numberText(std::round(stillFor)) +
                                  " s without motion";
            } else if (stuck && mayUnstick) {
                // Facing its target, yet still: obstacle points at (or in)
                // MRPT's robot shape that every forward path nears (rooms
                // M1 seed 8: stopped in a doorway 0.33 m from a post, MRPT's
                // "apparent collision" for 45 s, then its timeout). Turned
                // until its heading leads away from each of them (the first
                // step of every forward path leaves them), as near the target
                // as that allows and within turn_in_place_deg of it (MRPT's
                // forward-only PTGs must still aim at it).
                const double maxOff =
                    limitDeg > 0 ? (limitDeg - unstickDeg) * M_PI / 180 : M_PI;
                if (const auto e =
                        escapeHeading(pointsNearShape(), aimBearing, 0.0, maxOff);
                    e && std::abs(*e) * 180 / M_PI > unstickDeg / 3) {
                    m_turning = true, m_unsticking = true;
                    m_escapeHeading = pose.phi + *e;
                    bearing = *e;
                    countTurn();
                    m_unstickReason =
                        "obstacle at MRPT's robot shape after " +
                        numberText(std::round(stillFor)) +
                        " s without motion: turned away from it, " +
                        numberText(
                            std::round(std::abs(mrpt::math::wrapToPi(*e - aimBearing)) *
                                       180 / M_PI)) +
                        " deg off the target";
                }
            }
            if (m_turning) {
                mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
                cmd.lin_vel = 0;
                cmd.ang_vel =
                    (bearing > 0 ? 1 : -1) * riskOptions.turn_rate_deg * M_PI / 180;
                m_robot.changeSpeeds(cmd);
                m_last = {};
                m_last.turning = true;
                m_last.unsticking = m_unsticking;
                m_last.reason = m_unsticking ? m_unstickReason
                                : m_startTurning
                                    ? "aim " + numberText(std::round(deg)) +
                                          " deg off a standing robot, more than "
                                          "start_turn_deg"
                                    : "target " + numberText(std::round(deg)) +
                                          " deg off, more than turn_in_place_deg";
                return;
            }
        }
    }
    m_turning = m_unsticking = m_startTurning = false;
    m_escapeHeading.reset();
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
        m_following.reset();
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
    if (ev && ev->why == "new_target") {
        m_headBest = left, m_headwayAt = now;
        m_following.reset();
    } else if (ev || now < m_headwayAt)
        m_headBest = left;  // (a clock gone back: a new run)
    else if (left < m_headBest - 0.1)
        m_headBest = left, m_headwayAt = now;
    if (now < m_headwayAt)
        m_headwayAt = now;
    return true;
}

bool CRiskAwareReactiveNav::followPlan(const mrpt::math::TPose2D& pose, double allowed,
                                       bool lastTarget) {
    const auto& o = riskOptions;
    if (!(o.plan_follow_after > 0))
        return false;
    const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
    const double left = m_planner->remainingLength(pose);
    // the target's own zone: within its allowed distance MRPT marks it
    // reached; the route's end within MRPT's shape is finalApproach()'s
    const double endZone = lastTarget && o.final_approach_speed > 0
                               ? std::max(allowed, shapeRadius() + 0.1)
                               : allowed;
    if (!m_following) {
        if (now - m_headwayAt < o.plan_follow_after || left <= endZone ||
            blockedHere(m_followBlockedAt, pose, m_planner->current().points.back()))
            return false;
        m_following = TFollowing{now, pose, 0.0};
    } else {
        auto& f = *m_following;
        f.driven += std::hypot(pose.x - f.last.x, pose.y - f.last.y);
        f.last = pose;
        // a replan does not end it: the follower takes the current plan
        // each cycle (on a built map the sensed walls replan it often)
        if (f.driven >= o.plan_follow_distance || left <= endZone) {
            m_following.reset();  // far enough: MRPT steers again
            m_headBest = left, m_headwayAt = now;
            return false;
        }
    }
    const auto pts = sensedAround(pose, now);
    // the plan from the robot's nearest point on
    const auto& plan = m_planner->current().points;
    const size_t k0 = std::min(m_planner->nearestIndex(pose), plan.size());
    const std::vector<mrpt::math::TPoint2D> ahead(plan.begin() + long(k0), plan.end());
    const double wMax = o.turn_rate_deg * M_PI / 180;
    const auto cmd =
        planFollowCommand(pose, ahead, pts, shapeRadius() - o.plan_follow_margin,
                          o.plan_follow_speed, wMax, 0.5, 1.0, bodyFloor());
    if (cmd.blocked) {
        // the follower cannot either: MRPT (and its unstick turns) again,
        // and another try after plan_follow_after
        m_following.reset();
        m_headwayAt = now;
        m_followBlockedAt = mrpt::math::TPoint2D(pose.x, pose.y);
        return false;
    }
    char why[200];
    std::snprintf(why, sizeof(why),
                  "no headway along the global plan for %.0f s: the robot follows it "
                  "itself (%s), %.2f of %.2f m",
                  now - m_following->since + o.plan_follow_after, cmd.what.c_str(),
                  m_following->driven, o.plan_follow_distance);
    sendOwnCommand(cmd, "plan_follow", why);
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

bool CRiskAwareReactiveNav::blockedHere(std::optional<mrpt::math::TPoint2D>& at,
                                        const mrpt::math::TPose2D& pose,
                                        const mrpt::math::TPoint2D& target) {
    if (!m_blockedTarget ||
        std::hypot(m_blockedTarget->x - target.x, m_blockedTarget->y - target.y) > 1e-6) {
        m_followBlockedAt.reset(), m_finalBlockedAt.reset();
        m_blockedTarget = target;
    }
    if (at && std::hypot(pose.x - at->x, pose.y - at->y) > 0.1)
        at.reset();
    return at.has_value();
}

double CRiskAwareReactiveNav::bodyFloor() const {
    // [Robot] radius and 2 cm: the laser's range noise (1 cm) and more
    return std::min(robot.radius + 0.02, shapeRadius() - riskOptions.plan_follow_margin);
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

bool CRiskAwareReactiveNav::finalApproach(const mrpt::math::TPose2D& pose,
                                          const mrpt::math::TPoint2D& target,
                                          double allowed) {
    const auto& o = riskOptions;
    const double d = std::hypot(target.x - pose.x, target.y - pose.y);
    const double shape = shapeRadius();
    if (!(o.final_approach_speed > 0) || d <= allowed || d > shape + 0.1 ||
        blockedHere(m_finalBlockedAt, pose, target))
        return false;  // MRPT's (within allowed: its step marks it reached)
    const double now = mrpt::Clock::toDouble(mrpt::Clock::now());
    const auto pts = sensedAround(pose, now);
    // the plan follower on the straight stretch to the end (it turns in
    // place first when off it), slowly: a cycle's move (2 cm at 0.1 m/s
    // and 0.2 s) does not overshoot the allowed distance
    const std::vector<mrpt::math::TPoint2D> way{mrpt::math::TPoint2D(pose.x, pose.y),
                                                target};
    const auto cmd = planFollowCommand(pose, way, pts, shape - o.plan_follow_margin,
                                       o.final_approach_speed,
                                       o.turn_rate_deg * M_PI / 180, d, 1.0, bodyFloor());
    if (cmd.blocked) {
        m_finalBlockedAt = mrpt::math::TPoint2D(pose.x, pose.y);
        return false;
    }
    char why[200];
    std::snprintf(why, sizeof(why),
                  "the end %.2f m away, inside MRPT's robot shape (%.2f m): driven to "
                  "(%s)",
                  d, shape, cmd.what.c_str());
    sendOwnCommand(cmd, "final_approach", why);
    return true;
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
        // A risknav world senses now the scans MRPT's sensing then takes
        // (the same scans: CSimRobotInterface::senseAhead()), so the
        // limiters start ~0.2-0.3 ms of MRPT's step earlier (its sensing
        // and its work up to the first PTG); another robot's scans exist
        // only once MRPT sensed (STEP3_WSpaceToTPSpace()).
        auto* sim = dynamic_cast<sim::CSimRobotInterface*>(&m_robot);
        if (!sim)
            return;
        sim->senseAhead();
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

std::vector<mrpt::math::TPoint2D> CRiskAwareReactiveNav::pointsNearShape() const {
    // MRPT's shape as a disc of its farthest vertex (or its circular radius)
    double r = 0;
    for (const auto& v : m_robotShape)
        r = std::max(r, std::hypot(v.x, v.y));
    if (m_robotShape.empty())
        r = m_robotShapeCircularRadius;
    const double reach = r + kShapeEdge;
    std::vector<mrpt::math::TPoint2D> near;
    const auto& xs = m_WS_Obstacles.getPointsBufferRef_x();
    const auto& ys = m_WS_Obstacles.getPointsBufferRef_y();
    for (size_t k = 0; k < xs.size(); k++)
        if (std::hypot(xs[k], ys[k]) <= reach)
            near.emplace_back(xs[k], ys[k]);
    return near;
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
    if (!(L > 0) || m_guidePausedAt ||
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

void CRiskAwareReactiveNav::checkPtgBuildTime(const mrpt::config::CConfigFileBase& c,
                                              const std::string& shapeFrom) const {
    // (shapeRadius(): the polygon when there is one, as the diff-drive PTGs
    // take it; MRPT's file also gives a circle, for holonomic ones)
    if (m_engine)
        checkEngineBuildTime(CLayeredConfig(c, *m_engine), *this, shapeRadius(),
                             shapeFrom);
    else
        checkEngineBuildTime(c, *this, shapeRadius(), shapeFrom);
}

void CRiskAwareReactiveNav::loadConfigFile(const mrpt::config::CConfigFileBase& c) {
    // MRPT 2.5.8's CPTG_DiffDrive_alpha::saveToConfigFile() writes cte_a0v
    // as cte_a0w_deg: the text read is kept for saveConfigFile()
    auto keepA0w = [this](const mrpt::config::CConfigFileBase& src) {
        m_a0wText.assign(getPTG_count(), "");
        for (size_t i = 0; i < getPTG_count(); i++)
            if (dynamic_cast<const mrpt::nav::CPTG_DiffDrive_alpha*>(getPTG(i)))
                m_a0wText[i] =
                    src.read_string("CReactiveNavigationSystem",
                                    "PTG" + std::to_string(i) + "_cte_a0w_deg", "");
    };
    if (m_engine) {
        const CLayeredConfig layered(c, *m_engine);
        checkEngineText(layered);
        mrpt::nav::CReactiveNavigationSystem::loadConfigFile(layered);
        checkEngineTypes(layered, *this);
        checkEngineValues(layered, *this);
        keepA0w(layered);
    } else {
        checkEngineText(c);
        mrpt::nav::CReactiveNavigationSystem::loadConfigFile(c);
        checkEngineTypes(c, *this);
        checkEngineValues(c, *this);
        keepA0w(c);
    }
    // (with the config's robot shape; CNavigationRun checks again with the
    // shape it gives MRPT)
    checkPtgBuildTime(c);
    loadOptions(riskOptions, c, kSection);
    loadOptions(robot, c, "Robot");
    std::vector<CSpeedLimiter::Ptr> made;
    for (const auto& name : riskOptions.speed_limiters) {
        CSpeedLimiter::Ptr l;
        try {
            l = CSpeedLimiter::Factory(name);
        } catch (const CBadInputError& e) {  // unknown: names the known ones
            throw CBadInputError(configWhere(c) + "[" + kSection +
                                 "] speed_limiters: " + e.what());
        }
        if (!c.sectionExists(shortClassName(name)))
            throw CBadInputError(configWhere(c) + "[" + kSection +
                                 "] speed_limiters names " + name +
                                 " but the config has no [" + shortClassName(name) +
                                 "] section (its options; an empty section takes the "
                                 "defaults)");
        l->loadConfig(c, shortClassName(name));
        // candidate speeds the robot cannot reach would be silently capped
        if (const auto* a = dynamic_cast<const CAdaptiveSpeedLimiter*>(l.get());
            a && a->options.speed.speeds.front() > robot.max_v + 1e-9)
            throwBadKey(c, shortClassName(name), "speeds",
                        c.read_string(shortClassName(name), "speeds", ""),
                        "the fastest must be at most [Robot] max_v = " +
                            numberText(robot.max_v) + " m/s");
        made.push_back(l);
    }
    m_limiters = std::move(made);
}

void CRiskAwareReactiveNav::saveConfigFile(mrpt::config::CConfigFileBase& c) const {
    // Beyond MRPT 2.5.8, whose CReactiveNavigationSystem::saveConfigFile()
    // output does not load back: it writes each section twice with its keys
    // padded by spaces (an in-memory config then does not find them), and
    // neither the PTGs (PTG<n>_Type, PTG<n>_*) nor the robot shape. Its
    // text is read back (keys trimmed, sections merged), and the PTGs and the
    // shape are added as MRPT's own loader reads them.
    mrpt::config::CConfigFileMemory raw;
    mrpt::nav::CReactiveNavigationSystem::saveConfigFile(raw);
    std::string text;
    raw.getContent(text);
    CReadRecordingConfig all(text);
    const std::string nav = "CReactiveNavigationSystem";
    all.write(nav, "PTG_COUNT", int(getPTG_count()));
    for (size_t i = 0; i < getPTG_count(); i++) {
        const auto* ptg = getPTG(i);
        const std::string prefix = "PTG" + std::to_string(i) + "_";
        all.write(nav, prefix + "Type", std::string(ptg->GetRuntimeClass()->className));
        mrpt::config::CConfigFileMemory own;
        ptg->saveToConfigFile(own, "PTG");
        const mrpt::config::CConfigFileMemory parsed = reparsedConfig(own);
        std::vector<std::string> keys;
        parsed.getAllKeys("PTG", keys);
        for (const auto& k : keys)
            all.write(nav, prefix + k, parsed.read_string("PTG", k, ""));
        if (i < m_a0wText.size() && !m_a0wText[i].empty())
            all.write(nav, prefix + "cte_a0w_deg", m_a0wText[i]);
    }
    // MRPT 2.5.8 writes a default-constructed obstacle filter's options, not
    // those of the filter it uses
    if (const auto f = std::dynamic_pointer_cast<mrpt::maps::CPointCloudFilterByDistance>(
            m_WS_filter)) {
        mrpt::config::CConfigFileMemory own;
        f->options.saveToConfigFile(own, "CPointCloudFilterByDistance");
        copyConfigKeys(reparsedConfig(own), all);
    }
    // MRPT reads the shape into floats: 9 digits give the same floats back
    auto joined = [](const std::vector<double>& v) {
        std::ostringstream os;
        os.precision(9);
        for (size_t i = 0; i < v.size(); i++)
            os << (i ? " " : "") << float(v[i]);
        return os.str();
    };
    if (m_robotShape.size() > 0) {
        std::vector<double> xs, ys;
        m_robotShape.getAllVertices(xs, ys);
        all.write(nav, "RobotModel_shape2D_xs", joined(xs));
        all.write(nav, "RobotModel_shape2D_ys", joined(ys));
    }
    if (m_robotShapeCircularRadius > 0)
        all.write(nav, "RobotModel_circular_shape_radius", m_robotShapeCircularRadius);
    // MRPT also writes keys it never reads (e.g. [CMultiObjectiveMotion-
    // OptimizerBase] dummy, dummy2), which a loader that rejects unknown keys
    // refuses: only the keys a fresh engine reads from it are kept.
    {
        CNullRobot nobody;
        mrpt::nav::CReactiveNavigationSystem reader(nobody, false, false);
        reader.setMinLoggingLevel(mrpt::system::LVL_ERROR);
        reader.logging_enable_console_output = false;
        const_cast<mrpt::system::CTimeLogger&>(reader.getDelaysTimeLogger()).disable();
        reader.loadConfigFile(all);
    }
    copyConfigKeys(all, c, [&](const std::string& sec, const std::string& k) {
        return !all.wasRead(sec, k);
    });
    riskOptions.saveToConfigFile(c, kSection);
    robot.saveToConfigFile(c, "Robot");
    for (size_t i = 0; i < m_limiters.size(); i++)
        m_limiters[i]->saveConfig(c, shortClassName(riskOptions.speed_limiters[i]));
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
    // The raw scans (rays, not only their end points) when the robot is a
    // risknav world: the adaptive limiter maps free space along them.
    if (const auto* sim = dynamic_cast<const sim::CSimRobotInterface*>(&m_robot)) {
        in.scan = sim->lastScans().laser.get();
        in.scan2 = sim->lastScans().range2.get();
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
