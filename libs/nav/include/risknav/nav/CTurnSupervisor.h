#pragma once
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace risknav::nav {
/** Beyond MRPT: decides, each cycle of a navigation, whether the robot turns
 * in place instead of MRPT's engine stepping (CRiskAwareReactiveNav's
 * turn_in_place_deg, start_turn_deg, unstick_time, unstick_heading_deg):
 *  - a target farther off the heading than turn_in_place_deg (MRPT 2.5.8's
 *    forward-only PTGs cannot reach it), until within a third of that;
 *  - an aim farther off than start_turn_deg of a robot standing (under
 *    5 cm/s), until within a third of that;
 *  - a robot stuck (neither 5 cm nor 5 deg of motion for unstick_time) with
 *    its target more than unstick_heading_deg off, until within a third; or,
 *    facing its target, with obstacle points at MRPT's shape, to the heading
 *    nearest the target that leads away from them (escapeHeading()). At most
 *    3 such turns per target, counted again once the robot got 0.5 m nearer;
 *  - and it pauses the guide point of a robot stuck while guided, until it
 *    has moved 0.5 m or has a new target (guidePaused()).
 * It holds only the state of these decisions: what it is given (pose, speed,
 * target, time, where MRPT is aimed, the points at its shape) is all it
 * decides on, so it runs without an MRPT engine. */
class CTurnSupervisor {
  public:
    /** Its [CRiskAwareReactiveNav] keys (documented there); 0 = off. */
    struct TOptions {
        double turn_in_place_deg = 100;   ///< [deg]
        double turn_rate_deg = 30;        ///< [deg/s]
        double start_turn_deg = 45;       ///< [deg]
        double unstick_time = 5;          ///< [s]
        double unstick_heading_deg = 15;  ///< [deg]
    };
    TOptions options;

    /** One cycle's view of a robot navigating to a target not yet reached. */
    struct TInput {
        mrpt::math::TPose2D pose;  ///< world
        double speed = 0;          ///< [m/s] the robot's speed (world velocity)
        mrpt::math::TPoint2D target;
        double now = 0;  ///< [s] the navigation clock
        /** Where MRPT's engine is aimed instead of the target (a guide
         * point), as guidePaused() now says; empty or nullopt: the target.
         * Asked when a stuck robot may pause it, and once for the aim. */
        std::function<std::optional<mrpt::math::TPoint2D>()> guidePoint;
        /** Sensed obstacle points at (or in) MRPT's robot shape, robot
         * frame (pointsNearShape()); asked only for an escape turn. */
        std::function<std::vector<mrpt::math::TPoint2D>()> pointsNearShape;
    };

    /** A turn in place: command (0, angVel), MRPT does not step. */
    struct TTurn {
        double angVel = 0;        ///< [rad/s]
        bool unsticking = false;  ///< an unstick (or escape) turn
        std::string reason;
    };

    /** This cycle's decision (and its state updated): a turn, or nullopt:
     * MRPT steps (the turn, if any, has ended: as endTurn()). */
    std::optional<TTurn> step(const TInput& in);
    /** MRPT steps (no target, or one reached): a turn under way ends. The
     * stuck watch, the unstick count and the guide pause are kept. */
    void endTurn();

    /** Guide points are paused (a robot stuck while guided). */
    bool guidePaused() const { return m_guidePausedAt.has_value(); }
    /** A turn is under way. */
    bool turning() const { return m_turning; }

    /** [m] Points this far outside MRPT's robot shape count as at its edge
     * (a laser's noise moves them in and out of it). */
    static constexpr double kShapeEdge = 0.03;
    /** Turns to one target before the robot must have got 0.5 m nearer. */
    static constexpr int kMaxUnstickTurns = 3;
    /** The points of `obstacles` (robot frame) within `shapeRadius` +
     * kShapeEdge of the robot's centre: those at or in MRPT's robot shape
     * taken as a disc of that radius. Pure. */
    static std::vector<mrpt::math::TPoint2D> pointsNearShape(
        const mrpt::maps::CSimplePointsMap& obstacles, double shapeRadius);

  private:
    bool m_turning = false;
    bool m_unsticking = false;
    bool m_startTurning = false;
    /** Where and when the robot last moved 5 cm or turned 5 deg. */
    std::optional<mrpt::math::TPose2D> m_stillPose;
    double m_stillSince = 0;
    /** The last unstick turn: its target, the robot's distance to it, and
     * the turns to that target since the robot last got 0.5 m nearer. */
    struct TUnstick {
        mrpt::math::TPoint2D target;
        double distance = 0;
        int turns = 0;
    };
    std::optional<TUnstick> m_unstuck;
    std::string m_unstickReason;
    /** [rad, world] the heading an escape turn turns to. */
    std::optional<double> m_escapeHeading;
    /** Guide points paused: where, and the target then. */
    std::optional<std::pair<mrpt::math::TPoint2D, mrpt::math::TPoint2D>> m_guidePausedAt;
};
}  // namespace risknav::nav
