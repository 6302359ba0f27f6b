#pragma once
#include <risknav/sim/CSimWorld.h>

#include <mrpt/nav/reactive/CRobot2NavInterfaceForSimulator.h>

#include <optional>

namespace risknav::sim {
/** MRPT's robot interface on a risknav world, so that MRPT's
 * CReactiveNavigationSystem (or any CAbstractNavigator) drives it:
 *  - changeSpeeds() / stop() command the world, whose robot follows within
 *    its acceleration limits (MRPT's simulator base would jump to the speed);
 *  - getCurrentPoseAndSpeeds() reports the true pose (or a localization
 *    estimate, setLocalization()) and the world's drifting wheel odometry;
 *  - senseObstacles() returns the world's laser scan of this instant
 *    (people and clutter included) as robot-frame points.
 * The caller advances the world (world.step()) and MRPT's clock between
 * navigation steps. */
class CSimRobotInterface : public mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven {
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

    /** The pose to report instead of the truth (e.g. MCL); nullopt: the truth. */
    void setLocalization(const std::optional<mrpt::math::TPose2D>& pose) {
        m_localization = pose;
    }
    /** The scans of the latest senseObstacles() call. */
    const CSimWorld::TScans& lastScans() const { return m_last; }

  private:
    CSimWorld& m_world;
    std::optional<mrpt::math::TPose2D> m_localization;
    CSimWorld::TScans m_last;
};

}  // namespace risknav::sim
