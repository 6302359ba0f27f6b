#pragma once
#include <risknav/common/CRangeSensingRobot.h>
#include <risknav/sim/CSimWorld.h>

#include <mrpt/nav/reactive/CRobot2NavInterfaceForSimulator.h>

#include <optional>
#include <string>
#include <vector>

namespace risknav::sim {
/** MRPT's robot interface on a risknav world, so that MRPT's
 * CReactiveNavigationSystem (or any CAbstractNavigator) drives it:
 *  - changeSpeeds() / stop() command the world, whose robot follows within
 *    its acceleration limits (MRPT's simulator base would jump to the speed);
 *  - getCurrentPoseAndSpeeds() reports the true pose (or a localization
 *    estimate, setLocalization()) and the world's drifting wheel odometry;
 *  - senseObstacles() returns the world's laser scan of this instant
 *    (people and clutter included) as robot-frame points;
 *  - as a common::CRangeSensingRobot, it senses ahead of a navigator's
 *    engine (senseAhead()) and gives the raw scans (lastScan(), lastScan2()).
 * The caller advances the world (world.step()) and MRPT's clock between
 * navigation steps. */
class CSimRobotInterface : public mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven,
                           public common::CRangeSensingRobot {
  public:
    explicit CSimRobotInterface(CSimWorld& world);

    bool getCurrentPoseAndSpeeds(mrpt::math::TPose2D& curPose,
                                 mrpt::math::TTwist2D& curVelGlobal,
                                 mrpt::system::TTimeStamp& timestamp,
                                 mrpt::math::TPose2D& curOdometry,
                                 std::string& frame_id) override;
    bool changeSpeeds(const mrpt::kinematics::CVehicleVelCmd& cmd) override;
    bool stop(bool isEmergencyStop = true) override;
    bool senseObstacles(mrpt::maps::CSimplePointsMap& obstacles,
                        mrpt::system::TTimeStamp& timestamp) override;

    /** An event the navigator sent (MRPT's send*Event() calls), at world time t. */
    struct TNavEvent {
        double t = 0;
        std::string kind;  ///< navigation_start | navigation_end | waypoint_reached |
                           ///< waypoint_skipped | new_waypoint_target |
                           ///< navigation_error | way_seems_blocked |
                           ///< apparent_collision | cannot_get_closer
        int waypoint = -1;
    };
    void sendNavigationStartEvent() override;
    void sendNavigationEndEvent() override;
    void sendWaypointReachedEvent(int waypoint_index, bool reached_nSkipped) override;
    void sendNewWaypointTargetEvent(int waypoint_index) override;
    void sendNavigationEndDueToErrorEvent() override;
    void sendWaySeemsBlockedEvent() override;
    void sendApparentCollisionEvent() override;
    void sendCannotGetCloserToBlockedTargetEvent() override;
    /** Every event since construction, in order. */
    const std::vector<TNavEvent>& navEvents() const { return m_events; }

    /** The pose to report instead of the truth (e.g. MCL); nullopt: the truth. */
    void setLocalization(const std::optional<mrpt::math::TPose2D>& pose) {
        m_localization = pose;
    }
    /** Senses the world now; the next senseObstacles() returns these scans
     * instead of sensing again (so a localizer can use the scan the navigator
     * will see, before the navigator asks for the pose). */
    const CSimWorld::TScans& senseNow();
    /** The scans the next senseObstacles() returns: those of a senseNow()
     * not handed out yet, else sensed now (senseNow()). Lets a navigator
     * start work on the scans before MRPT's step senses, without sensing
     * twice. */
    void senseAhead() override {
        if (!m_fresh)
            senseNow();
    }
    /** The scans of the latest senseNow() / senseObstacles() call. */
    const CSimWorld::TScans& lastScans() const { return m_last; }
    /** lastScans()' laser scan. */
    const mrpt::obs::CObservation2DRangeScan* lastScan() const override {
        return m_last.laser.get();
    }
    /** lastScans()' RANGE2 scan (null without that sensor). */
    const mrpt::obs::CObservation2DRangeScan* lastScan2() const override {
        return m_last.range2.get();
    }

  private:
    CSimWorld& m_world;
    std::optional<mrpt::math::TPose2D> m_localization;
    CSimWorld::TScans m_last;
    bool m_fresh = false;
    std::vector<TNavEvent> m_events;
    void record(const char* kind,
                int waypoint = -1);  // m_last sensed by senseNow(), not yet handed out
};

}  // namespace risknav::sim
