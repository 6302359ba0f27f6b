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

const CSimWorld::TScans& CSimRobotInterface::senseNow() {
    m_last = m_world.sense();
    m_fresh = true;
    return m_last;
}

bool CSimRobotInterface::senseObstacles(mrpt::maps::CSimplePointsMap& obstacles,
                                        mrpt::system::TTimeStamp& timestamp) {
    if (!m_fresh)
        m_last = m_world.sense();
    m_fresh = false;
    timestamp = mrpt::Clock::now();
    obstacles.clear();
    obstacles.insertionOptions.minDistBetweenLaserPoints = 0;
    obstacles.loadFromRangeScan(*m_last.laser);  // robot frame: no robot pose given
    return true;
}

void CSimRobotInterface::record(const char* kind, int waypoint) {
    m_events.push_back({m_world.time(), kind, waypoint});
}

// Each event is recorded and then passed on to MRPT's default (which logs it).
void CSimRobotInterface::sendNavigationStartEvent() {
    record("navigation_start");
    CRobot2NavInterfaceForSimulator_DiffDriven::sendNavigationStartEvent();
}
void CSimRobotInterface::sendNavigationEndEvent() {
    record("navigation_end");
    CRobot2NavInterfaceForSimulator_DiffDriven::sendNavigationEndEvent();
}
void CSimRobotInterface::sendWaypointReachedEvent(int i, bool reached) {
    record(reached ? "waypoint_reached" : "waypoint_skipped", i);
    CRobot2NavInterfaceForSimulator_DiffDriven::sendWaypointReachedEvent(i, reached);
}
void CSimRobotInterface::sendNewWaypointTargetEvent(int i) {
    record("new_waypoint_target", i);
    CRobot2NavInterfaceForSimulator_DiffDriven::sendNewWaypointTargetEvent(i);
}
void CSimRobotInterface::sendNavigationEndDueToErrorEvent() {
    record("navigation_error");
    CRobot2NavInterfaceForSimulator_DiffDriven::sendNavigationEndDueToErrorEvent();
}
void CSimRobotInterface::sendWaySeemsBlockedEvent() {
    record("way_seems_blocked");
    CRobot2NavInterfaceForSimulator_DiffDriven::sendWaySeemsBlockedEvent();
}
void CSimRobotInterface::sendApparentCollisionEvent() {
    record("apparent_collision");
    CRobot2NavInterfaceForSimulator_DiffDriven::sendApparentCollisionEvent();
}
void CSimRobotInterface::sendCannotGetCloserToBlockedTargetEvent() {
    record("cannot_get_closer");
    CRobot2NavInterfaceForSimulator_DiffDriven::sendCannotGetCloserToBlockedTargetEvent();
}

}  // namespace risknav::sim
