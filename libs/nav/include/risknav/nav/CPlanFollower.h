#pragma once
#include <risknav/nav/plan_follow.h>
#include <risknav/planning/CGlobalPlanner.h>

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace risknav::nav {
/** Beyond MRPT: when the navigator drives the robot itself instead of
 * MRPT's engine (CRiskAwareReactiveNav's plan_follow_after and
 * final_approach_speed), and with which command (planFollowCommand()):
 *  - followPlan(): a robot that has not got 0.1 m further along the global
 *    plan for plan_follow_after follows it itself until it has driven
 *    plan_follow_distance, or its end zone is reached, or it is blocked;
 *  - finalApproach(): the route's end, nearer than MRPT's shape radius +
 *    0.1 m yet not within its allowed distance, is driven to straight.
 * Where either found every motion blocked it is not tried again until the
 * robot has moved 0.1 m from there or has a new target (else it and the
 * unstick turns undo each other). It holds the headway and following state;
 * the planner, the sensed points and the clock are given. */
class CPlanFollower {
  public:
    /** Its [CRiskAwareReactiveNav] keys (documented there). */
    struct TOptions {
        double plan_follow_after = 8;       ///< [s] 0 = off
        double plan_follow_speed = 0.2;     ///< [m/s]
        double plan_follow_distance = 1.0;  ///< [m]
        double plan_follow_margin = 0.05;   ///< [m]
        double final_approach_speed = 0.1;  ///< [m/s] 0 = off
        double turn_rate_deg = 30;          ///< [deg/s] the fastest turn
    };
    TOptions options;

    /** The robot's body: MRPT's shape as a disc of its farthest vertex (or
     * its circular radius) and [Robot] radius, [m]. */
    struct TBody {
        double shapeRadius = 0;
        double robotRadius = 0;
    };
    /** The obstacle points the robot's own motion keeps its body off (robot
     * frame, sensed now and remembered); asked once a command is to be
     * made. */
    using TSensed = std::function<std::vector<mrpt::math::TPoint2D>()>;

    /** A command of the navigator's own. */
    struct TDrive {
        TFollowCommand cmd;
        const char* mode = "";  ///< "plan_follow" | "final_approach"
        std::string reason;
    };

    /** After the planner's cycle (`left` [m]: the way left along its plan,
     * `now` [s]): `replanned` a new plan, `newTarget` for a new target
     * (headway counted from now, following ends). */
    void planUpdated(bool replanned, bool newTarget, double left, double now);
    /** No plan: following ends. */
    void cancel() { m_following.reset(); }

    /** plan_follow_after: this cycle's command following `planner`'s plan
     * (nullopt: MRPT steps). `allowed`: the target's allowed distance,
     * `lastTarget`: it is the route's end. */
    std::optional<TDrive> followPlan(const mrpt::math::TPose2D& pose, double now,
                                     const planning::CGlobalPlanner& planner,
                                     const TBody& body, double allowed, bool lastTarget,
                                     const TSensed& sensed);
    /** final_approach_speed: this cycle's command driving to the route's
     * end `target` (nullopt: MRPT steps; within `allowed` its step marks it
     * reached). */
    std::optional<TDrive> finalApproach(const mrpt::math::TPose2D& pose,
                                        const mrpt::math::TPoint2D& target,
                                        double allowed, const TBody& body,
                                        const TSensed& sensed);

    /** [m] the nearest the robot's own driving lets a sensed point come to
     * its centre, whatever the start: [Robot] radius + 2 cm (the laser's
     * range noise, 1 cm, and more), at most the shape's radius less
     * plan_follow_margin. */
    double bodyFloor(const TBody& body) const;
    /** The robot follows the plan itself. */
    bool following() const { return m_following.has_value(); }

  private:
    /** [m] the least way left along the plans to this target, and when the
     * robot last got 0.1 m further (a replan does not count as headway). */
    double m_headBest = 0;
    double m_headwayAt = 0;
    /** While the robot follows the plan itself: since when, the pose of
     * the last cycle and the distance driven since. */
    struct TFollowing {
        double since = 0;
        mrpt::math::TPose2D last;
        double driven = 0;
    };
    std::optional<TFollowing> m_following;
    /** Where followPlan() / finalApproach() found every motion blocked, and
     * the target then. */
    std::optional<mrpt::math::TPoint2D> m_followBlockedAt, m_finalBlockedAt;
    std::optional<mrpt::math::TPoint2D> m_blockedTarget;
    bool blockedHere(std::optional<mrpt::math::TPoint2D>& at,
                     const mrpt::math::TPose2D& pose, const mrpt::math::TPoint2D& target);
};
}  // namespace risknav::nav
