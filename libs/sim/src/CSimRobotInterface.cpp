#include <risknav/sim/CSimRobotInterface.h>

#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/maps/CSimplePointsMap.h>

namespace risknav::sim {
CSimRobotInterface::CSimRobotInterface(CSimWorld& world)
    : mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven(world.vehicle()),
      m_world(world) {}

bool CSimRobotInterface::getCurrentPoseAndSpeeds(mrpt::math::TPose2D& curPose,
                                                 mrpt::math::TTwist2D& curVelGlobal,
                                                 mrpt::system::TTimeStamp& timestamp,
                                                 mrpt::math::TPose2D& curOdometry,
                                                 std::string& frame_id) {
    curPose = m_localization ? *m_localization : m_world.truePose();
    curVelGlobal = m_world.velocity();
    timestamp = mrpt::Clock::now();  // the navigator measures delays on MRPT's clock
    curOdometry = m_world.odometricPose();
    frame_id = "map";
    return true;
}

bool CSimRobotInterface::changeSpeeds(const mrpt::kinematics::CVehicleVelCmd& cmd) {
    const auto* dd =
        dynamic_cast<const mrpt::kinematics::CVehicleVelCmd_DiffDriven*>(&cmd);
    if (!dd)
        return false;  // not a differential-drive command: refuse, MRPT logs it
    m_world.command(dd->lin_vel, dd->ang_vel);
    return true;
}

bool CSimRobotInterface::stop(bool /*isEmergencyStop*/) {
    m_world.command(0, 0);
    return true;
}

bool CSimRobotInterface::senseObstacles(mrpt::maps::CSimplePointsMap& obstacles,
                                        mrpt::system::TTimeStamp& timestamp) {
    m_last = m_world.sense();
    timestamp = mrpt::Clock::now();
    obstacles.clear();
    obstacles.insertionOptions.minDistBetweenLaserPoints = 0;
    obstacles.loadFromRangeScan(*m_last.laser);  // robot frame: no robot pose given
    return true;
}

}  // namespace risknav::sim
