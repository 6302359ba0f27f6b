#pragma once
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/nav/reactive/CRobot2NavInterface.h>

#include <memory>
#include <string>

namespace risknav::nav {
/** A robot that does nothing: for an MRPT navigator that only loads or
 * checks a config (its destructor stops the robot it is given, so not the
 * one being driven). Senses nothing, knows no pose, refuses commands. */
class CNullRobot : public mrpt::nav::CRobot2NavInterface {
  public:
    bool getCurrentPoseAndSpeeds(mrpt::math::TPose2D&, mrpt::math::TTwist2D&,
                                 mrpt::system::TTimeStamp&, mrpt::math::TPose2D&,
                                 std::string&) override {
        return false;
    }
    bool changeSpeeds(const mrpt::kinematics::CVehicleVelCmd&) override { return false; }
    bool stop(bool) override { return true; }
    mrpt::kinematics::CVehicleVelCmd::Ptr getEmergencyStopCmd() override {
        return getStopCmd();
    }
    mrpt::kinematics::CVehicleVelCmd::Ptr getStopCmd() override {
        return std::make_shared<mrpt::kinematics::CVehicleVelCmd_DiffDriven>();
    }
    bool senseObstacles(mrpt::maps::CSimplePointsMap&,
                        mrpt::system::TTimeStamp&) override {
        return false;
    }
};
}  // namespace risknav::nav
