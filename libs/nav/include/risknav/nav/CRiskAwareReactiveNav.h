#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/CSpeedLimiter.h>
#include <risknav/common/TRobotOptions.h>
#include <risknav/nav/CPlanFollower.h>
#include <risknav/nav/CTurnSupervisor.h>
#include <risknav/nav/plan_follow.h>
#include <risknav/planning/CGlobalPlanner.h>

#include <mrpt/nav/reactive/CReactiveNavigationSystem.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace risknav::nav {
/** MRPT's reactive navigation engine with risknav's speed limiters inside it
 * (DESIGN.md "Plugins inside MRPT's reactive engine"): a
 * CReactiveNavigationSystem that keeps all of MRPT's config sections and
 * behaviour (a config that works with the bare engine works with it), and
 * each cycle asks its limiters, created by class name from
 * [CRiskAwareReactiveNav] speed_limiters through MRPT's class registry, for
 * the highest speed they allow. The smallest limit wins and scales the
 * command MRPT chose (v and w together, the curvature kept) in the
 * engine's own generate_vel_cmd(); the winning limiter, its limit and reason
 * go into the cycle's navlog record (CLogFileRecord::additional_debug_msgs
 * "speed_limiter", values "speed_limit" / "speed_desired"), so MRPT's
 * navlog-viewer shows them. Each limiter reads its options from the section
 * named after its class (e.g. [CStoppingDistanceLimiter]); the robot's
 * stopping model from [Robot]. */
class CRiskAwareReactiveNav : public mrpt::nav::CReactiveNavigationSystem {
  public:
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "CRiskAwareReactiveNav"; }
        /** Limiter class names, applied in this order (the first of equal
         * limits is the one recorded). Empty: the bare MRPT engine. */
        std::vector<std::string> speed_limiters;
        /** [deg] a target farther off the heading than this is turned to in
         * place first (0 = off): MRPT 2.5.8's forward-only PTGs cannot reach
         * a target behind the robot (its score formulas then throw
         * "Undefined symbol: target_d_norm" every cycle), and a reversing
         * PTG would drive a robot with a forward laser backwards blind. */
        double turn_in_place_deg = 100;
        double turn_rate_deg = 30;  ///< [deg/s] of that turn
        /** [deg] a robot standing still (under 5 cm/s) whose aim (the
         * global plan's guide point, else the target) is farther off its
         * heading than this turns to it in place first, until within a third
         * of it (0 = off). Beyond MRPT: its forward PTGs from a standstill
         * find no motion toward a point 40-100 deg to the side of a robot
         * beside a wall, and fail cycle after cycle. */
        double start_turn_deg = 45;
        /** [s] Beyond MRPT: a robot that has neither left a 5 cm circle
         * nor turned 5 deg for this long while MRPT navigates (MRPT 2.5.8
         * can creep at 1e-4 m/s for minutes at a turn, its own "not
         * approaching" alarm silent) is turned in place toward its target
         * when that is more than unstick_heading_deg off its heading, until
         * it is within a third of that angle (0 = off, else >= 2 s). A
         * robot that faces its target yet has sensed obstacle points at its
         * MRPT shape (within 3 cm of it) is turned instead to the heading
         * nearest the target that leads away from all of them (no more than
         * turn_in_place_deg - unstick_heading_deg off it; escapeHeading()):
         * MRPT 2.5.8 takes no forward path that nears such a point. At most
         * 3 turns per target, counted again once the robot got 0.5 m nearer
         * to it, so that MRPT's own error at an unreachable target shows. */
        double unstick_time = 5;
        double unstick_heading_deg = 15;  ///< [deg] see unstick_time
        /** [m] Beyond the papers and MRPT: while a limiter plans a way
         * itself (CAdaptiveSpeedLimiter, on its own map of an unknown world),
         * MRPT's engine steers to the point this far ahead on that way
         * (speed::lookaheadPoint) instead of straight at the waypoint,
         * which a purely reactive engine cannot reach round a wall; the
         * waypoint is still what is reached, timed and logged. Used while
         * the waypoint is farther than this. 0 = off. */
        double guide_lookahead = 0;
        /** [s] Beyond MRPT: with a global plan (CGlobalPlanner), a robot
         * that has not got 0.1 m further along it for this long (MRPT 2.5.8
         * stands at ~1e-4 m/s, dithering a few degrees, in a gap its shape
         * fits by a few cm) follows the plan itself (planFollowCommand(),
         * pure pursuit, fresh scans checked) at up to plan_follow_speed
         * until it has driven plan_follow_distance (along whichever plan is
         * current), then MRPT steers again (0 = off). Blocked, it hands back at once.
         * It stops short of the target's allowed distance (MRPT marks it
         * reached), of the route's end at final_approach_speed's reach. */
        double plan_follow_after = 8;
        double plan_follow_speed = 0.2;     ///< [m/s] see plan_follow_after
        double plan_follow_distance = 1.0;  ///< [m] see plan_follow_after
        /** [m] how far inside MRPT's robot shape a sensed point may come
         * while the robot follows the plan itself (the plan keeps the whole
         * shape off the map's obstacles: this is room for tracking error). */
        double plan_follow_margin = 0.05;
        /** [m/s] Beyond MRPT: the route's end, nearer than MRPT's robot
         * shape's radius + 0.1 m yet not within its allowed distance, is
         * driven to straight at this speed (fresh scans checked as
         * plan_follow_margin says); MRPT's next step marks it reached.
         * MRPT 2.5.8 maps a target inside its shape to no motion and stands
         * (0.15-0.3 m off an end 0.15 m asked, for minutes). 0 = off. */
        double final_approach_speed = 0.1;

      protected:
        void declare(Visitor& v) override;
        /** At most 16 limiters, none twice; unstick_time and
         * plan_follow_after 0 (off) or at least 2 s. */
        void validateRules() const override;
    };

    /** What limited the last command. */
    struct TLimitRecord {
        std::string limiter;  ///< class name; "" when none limited
        std::string reason;
        double desired = 0;    ///< [m/s] |v| MRPT chose
        double limit = 0;      ///< [m/s] the smallest limit (desired when none limited)
        bool turning = false;  ///< this cycle turned in place (MRPT did not plan)
        bool unsticking = false;  ///< that turn is an unstick turn (unstick_time)
    };

    CRiskAwareReactiveNav(mrpt::nav::CRobot2NavInterface& robot,
                          bool enableConsoleOutput = false, bool enableLogFile = false,
                          const std::string& logFileDirectory = "reactivenav.logs");

    TOptions riskOptions;         ///< [CRiskAwareReactiveNav]
    common::TRobotOptions robot;  ///< [Robot]: radius, decel, t_delay for the limiters

    /** MRPT's step; or, with a target not yet reached, the global
     * planner's cycle, then the navigator's own driving (CPlanFollower:
     * plan_follow_after, final_approach_speed) or a turn in place
     * (CTurnSupervisor: turn_in_place_deg, start_turn_deg, unstick_time)
     * instead of it. */
    void navigationStep() override;

    /** MRPT's loadConfigFile() plus [CRiskAwareReactiveNav], [Robot] and each
     * limiter's section. An unknown limiter name throws CBadInputError
     * naming the known ones. Values MRPT 2.5.8 takes unchecked throw
     * CBadInputError naming the key: robotMax_V_mps / robotMax_W_degps not in
     * [0.01, 100] m/s / [0.1, 3600] deg/s; a PTG's refDistance not in
     * [0.1, 100] m, num_paths not in [4, 2000], resolution not in [5 mm, 1 m]
     * or more than 1000 cells over refDistance, v_max / w_max as the
     * robot's, K = 0, score_priority < 0 or all 0; the PTGs' build over ~1
     * min (checkPtgBuildTime()); the holonomic method's lists, phases and
     * normalized distances; score formulas that do not compile or loop.
     * The checks and what MRPT did without them: README, Reliability. */
    void loadConfigFile(const mrpt::config::CConfigFileBase& c) override;
    /** Throws CBadInputError naming a PTG's num_paths when MRPT's
     * collision-grid PTGs, as loaded from `c` (with the engine config),
     * would take it over ~1 min to build for the robot shape set now (a
     * model fitted to builds measured here: paths, cells, reach, turning
     * radius, robot area; `shapeFrom`: where the shape came from, for the
     * message). loadConfigFile() calls it; call it again after
     * changeRobotShape(). */
    void checkPtgBuildTime(const mrpt::config::CConfigFileBase& c,
                           const std::string& shapeFrom = "") const;
    void saveConfigFile(mrpt::config::CConfigFileBase& c) const override;
    /** MRPT's engine sections from `engine` (e.g. the user's MRPT
     * reactive-navigation file), keys of the config given to loadConfigFile()
     * overriding its keys; nullptr: that config alone. Not owned. */
    void setEngineConfig(const mrpt::config::CConfigFileBase* engine) {
        m_engine = engine;
    }

    const std::vector<common::CSpeedLimiter::Ptr>& limiters() const { return m_limiters; }

    /** A global planner on the known map (nullptr: none, MRPT's engine aims
     * straight at each waypoint or at a limiter's guide point). Each cycle
     * it replans as needed (CGlobalPlanner::update()), takes in what the
     * engine sensed, and MRPT's engine is aimed at its guide point; MRPT's
     * "not approaching the target" alarm then watches the way left along
     * the plan, not the straight distance. A target it finds no way to
     * stops the navigation (NAV_ERROR), planFailure() says why. */
    void setGlobalPlanner(std::shared_ptr<planning::CGlobalPlanner> p) {
        m_planner = std::move(p);
    }
    const std::shared_ptr<planning::CGlobalPlanner>& globalPlanner() const {
        return m_planner;
    }
    /** The plan that found no way, when that stopped the navigation. */
    const std::optional<planning::TGlobalPlan>& planFailure() const {
        return m_planFailure;
    }
    const TLimitRecord& lastLimit() const { return m_last; }

    /** What MRPT aims at while navigating: the first waypoint not yet
     * reached (or the single target), with its allowed distance. */
    struct TCurrentTarget {
        mrpt::math::TPoint2D point;
        double allowedDistance = 0;
        bool last = true;  ///< the route's end (no waypoint after it)
    };
    std::optional<TCurrentTarget> currentTarget() const;
    /** MRPT's, and the request is known as a target before MRPT's first
     * step takes it (the first waypoint is turned to, and planned to, from
     * the first cycle on). */
    void navigateWaypoints(const mrpt::nav::TWaypointSequence& request) override;
    /** A request MRPT's step has not taken yet (turning to it first): MRPT
     * is still IDLE, the navigation has not ended. */
    bool requestPending() const { return m_requestPending; }
    /** Where MRPT's engine is aimed from `pose` on the way to `target`: the
     * first limiter's guide point (CSpeedLimiter::guidePoint) while
     * guide_lookahead > 0 and the target is farther than that; else
     * nullopt (straight at the target). Paused for a robot stuck while
     * guided, until it has moved 0.5 m or has a new target. */
    std::optional<mrpt::math::TPoint2D> guidePoint(
        const mrpt::math::TPose2D& pose, const mrpt::math::TPoint2D& target) const;

  protected:
    /** What the limiters see this cycle: the robot, the believed pose, the
     * sensed points, the target, the clock, the raw scans when the robot
     * gives them (common::CRangeSensingRobot), and MRPT's chosen trajectory (`movement`,
     * may be null) sampled every ~5 cm over d_stop(desired) + radius + 1 m. */
    common::TSpeedLimitInput limiterInput(
        const mrpt::nav::TCandidateMovementPTG* movement, double desired) const;
    /** MRPT's command, then the smallest limit of the limiters applied to it. */
    double generate_vel_cmd(const mrpt::nav::TCandidateMovementPTG& in_movement,
                            mrpt::kinematics::CVehicleVelCmd::Ptr& new_vel_cmd) override;
    /** MRPT's step, aimed at the guide point (guide_lookahead) when a
     * limiter gives one; the waypoint is put back after it. On a robot that
     * senses ahead (common::CRangeSensingRobot, e.g. risknav's simulated
     * one) the limiters observe() the step's scans before it starts
     * (observeNow()). */
    void performNavigationStep() override;
    /** MRPT's mapping of the sensed obstacles into a PTG's TP-space; its
     * first call in a step (MRPT has sensed, and evaluates its motions from
     * here on) first gives every limiter observe() on what was sensed, if
     * they have not observed this step yet (another robot than a risknav
     * world: the adaptive limiter starts its cycle beside the engine's
     * evaluation). */
    void STEP3_WSpaceToTPSpace(const size_t ptg_idx, std::vector<double>& out_TPObstacles,
                               mrpt::nav::ClearanceDiagram& out_clearance,
                               const mrpt::math::TPose2D& rel_pose_PTG_origin_wrt_sense,
                               const bool eval_clearance) override;
    /** MRPT's record, plus the limiter that won this cycle. */
    void loggingGetWSObstaclesAndShape(mrpt::nav::CLogFileRecord& out_log) override;

  private:
    /** Waits for the work the limiters' observe() started; an error it
     * ended with stops the navigation as MRPT stops it for an error in its
     * step (NAV_ERROR with the message), or is dropped (`quiet`). */
    void finishObserved(bool quiet);
    /** The limiters' observe() of this step, once. `beforeSensing`: only on
     * a robot that senses ahead (common::CRangeSensingRobot), whose scans it
     * senses ahead of MRPT (the same scans MRPT then gets; the input has no
     * MRPT point map yet); another robot: nothing, the limiters observe once
     * MRPT has sensed (STEP3_WSpaceToTPSpace()). */
    void observeNow(bool beforeSensing);
    /** currentTarget() from a copy of MRPT's waypoint status. */
    std::optional<TCurrentTarget> currentTarget(
        const mrpt::nav::TWaypointStatusSequence& st) const;
    std::vector<common::CSpeedLimiter::Ptr> m_limiters;
    TLimitRecord m_last;
    bool m_observeDue = false;  ///< this step's limiters have not observed yet
    /** While the step aims at a guide point: the waypoint MRPT's target
     * stands for (what the limiters are told). */
    std::optional<mrpt::math::TPoint2D> m_realTarget;
    const mrpt::config::CConfigFileBase* m_engine = nullptr;
    std::shared_ptr<planning::CGlobalPlanner> m_planner;
    std::optional<planning::TGlobalPlan> m_planFailure;
    double m_planBest = 0;  ///< [m] the least way left along the plan so far
    /** The navigator's own driving: plan following, final approach. */
    CPlanFollower m_follower;
    /** Turns in place instead of MRPT's step. */
    CTurnSupervisor m_turns;
    /** riskOptions into m_follower's and m_turns' options. */
    void syncOptions();
    /** Sends the navigator's own command (not MRPT's) and records it as
     * the cycle's limit, `limiter` and `reason`. */
    void sendOwnCommand(const TFollowCommand& cmd, const char* limiter,
                        const std::string& reason);
    /** [m] MRPT's robot shape as a disc of its farthest vertex (or its
     * circular radius). */
    double shapeRadius() const;
    /** Fresh obstacle points from the robot (robot frame), also given to
     * the global planner; MRPT does not sense while the navigator drives. */
    std::vector<mrpt::math::TPoint2D> senseNow(const mrpt::math::TPose2D& pose,
                                               double now);
    /** senseNow() and the global planner's remembered sensed cells within
     * the shape's radius + 0.5 m (robot frame): what the robot's own
     * motions (plan following, final approach) keep their body off. */
    std::vector<mrpt::math::TPoint2D> sensedAround(const mrpt::math::TPose2D& pose,
                                                   double now);
    /** The planner's cycle: replan for `pose` going to `target`. False: no
     * way (the navigation was stopped). */
    bool updatePlanner(const mrpt::math::TPose2D& pose,
                       const mrpt::math::TPoint2D& target);
    /** A waypoint request MRPT's step has not taken yet (MRPT is IDLE). */
    bool m_requestPending = false;
    /** Each PTG's cte_a0w_deg as read (CPTG_DiffDrive_alpha; else ""). */
    std::vector<std::string> m_a0wText;
};

/** Registers libs/nav's MRPT classes and the limiters of the libraries below
 * (see registerAllClasses_sim()). Idempotent. */
void registerAllClasses_nav();

}  // namespace risknav::nav
