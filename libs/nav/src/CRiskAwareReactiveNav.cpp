#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/nav/CLayeredConfig.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/sim/CSimRobotInterface.h>

#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/nav/reactive/CLogFileRecord.h>

#include <cmath>
#include <sstream>

using namespace risknav::common;

namespace risknav::nav {
namespace {
const char* kSection = "CRiskAwareReactiveNav";

// The class name without its namespace: the limiter's config section.
std::string shortName(const std::string& n) {
    const auto p = n.rfind("::");
    return p == std::string::npos ? n : n.substr(p + 2);
}
}  // namespace

void CRiskAwareReactiveNav::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s) {
    const std::string list = readString(c, s, "speed_limiters", "");
    speed_limiters.clear();
    std::istringstream in(list);
    for (std::string name; in >> name;)
        speed_limiters.push_back(name);
}

void CRiskAwareReactiveNav::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                       const std::string& s) const {
    std::string list;
    for (const auto& n : speed_limiters)
        list += (list.empty() ? "" : " ") + n;
    writeKey(c, s, "speed_limiters", list);
}

void CRiskAwareReactiveNav::TOptions::validate() const {
    checkRule(speed_limiters.size() <= 16, kSection, "speed_limiters",
              std::to_string(speed_limiters.size()) + " names", "at most 16 limiters");
}

CRiskAwareReactiveNav::CRiskAwareReactiveNav(mrpt::nav::CRobot2NavInterface& r,
                                             bool console, bool logFile,
                                             const std::string& logDir)
    : mrpt::nav::CReactiveNavigationSystem(r, console, logFile, logDir) {
    registerAllClasses_nav();
}

void CRiskAwareReactiveNav::loadConfigFile(const mrpt::config::CConfigFileBase& c) {
    if (m_engine)
        mrpt::nav::CReactiveNavigationSystem::loadConfigFile(CLayeredConfig(c, *m_engine));
    else
        mrpt::nav::CReactiveNavigationSystem::loadConfigFile(c);
    loadOptions(riskOptions, c, kSection);
    loadOptions(robot, c, "Robot");
    std::vector<CSpeedLimiter::Ptr> made;
    for (const auto& name : riskOptions.speed_limiters) {
        auto l =
            CSpeedLimiter::Factory(name);  // unknown: CBadInputError, names the known
        if (!c.sectionExists(shortName(name)))
            throw CBadInputError(configWhere(c) + "[" + kSection + "] speed_limiters names " +
                                 name + " but the config has no [" + shortName(name) +
                                 "] section (its options; an empty section takes the "
                                 "defaults)");
        l->loadConfig(c, shortName(name));
        made.push_back(l);
    }
    m_limiters = std::move(made);
}

void CRiskAwareReactiveNav::saveConfigFile(mrpt::config::CConfigFileBase& c) const {
    mrpt::nav::CReactiveNavigationSystem::saveConfigFile(c);
    riskOptions.saveToConfigFile(c, kSection);
    robot.saveToConfigFile(c, "Robot");
    for (size_t i = 0; i < m_limiters.size(); i++)
        m_limiters[i]->saveConfig(c, shortName(riskOptions.speed_limiters[i]));
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
    TSpeedLimitInput in;
    in.robot = &robot;
    in.pose = m_curPoseVel.pose;
    in.desiredSpeed = desired;
    in.obstacles = &m_WS_Obstacles;
    in.time = mrpt::Clock::toDouble(mrpt::Clock::now());
    if (m_navigationParams)
        in.target = mrpt::math::TPoint2D(m_navigationParams->target.target_coords.x,
                                         m_navigationParams->target.target_coords.y);
    // The raw scans (rays, not only their end points) when the robot is a
    // risknav world: the adaptive limiter maps free space along them.
    if (const auto* sim = dynamic_cast<const sim::CSimRobotInterface*>(&m_robot)) {
        in.scan = sim->lastScans().laser.get();
        in.scan2 = sim->lastScans().range2.get();
    }
    for (size_t i = 0; i < m_limiters.size(); i++) {
        const TSpeedLimit l = m_limiters[i]->limit(in);
        if (l.maxSpeed < m_last.limit) {
            m_last.limit = l.maxSpeed;
            m_last.limiter = shortName(riskOptions.speed_limiters[i]);
            m_last.reason = l.reason;
        }
    }
    if (m_last.limit >= desired)
        return scale;
    const double s = std::max(0.0, m_last.limit / desired);
    auto* dd = dynamic_cast<mrpt::kinematics::CVehicleVelCmd_DiffDriven*>(new_vel_cmd.get());
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
}

}  // namespace risknav::nav
