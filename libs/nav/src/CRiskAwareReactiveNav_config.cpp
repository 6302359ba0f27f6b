// CRiskAwareReactiveNav's config: its [CRiskAwareReactiveNav] options, and
// MRPT's engine config loaded (with the checks MRPT 2.5.8 lacks) and saved
// (so that it loads back).
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CLayeredConfig.h>
#include <risknav/nav/CNullRobot.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/nav/engine_config_check.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/CPointCloudFilterByDistance.h>
#include <mrpt/nav/tpspace/CPTG_DiffDrive_alpha.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace risknav::common;

namespace risknav::nav {
namespace {
const char* kSection = "CRiskAwareReactiveNav";

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

void CRiskAwareReactiveNav::TOptions::declare(Visitor& v) {
    // the class names are no fixed set (MRPT's class registry says which
    // exist, loadConfigFile() asks it): the list is held as its text
    std::string list;
    for (const auto& n : speed_limiters)
        list += (list.empty() ? "" : " ") + n;
    v.text(list, "speed_limiters", false,
           "limiter class names, applied in this order (none: the bare MRPT engine)");
    std::vector<std::string> names;
    std::istringstream in(list);
    for (std::string name; in >> name;)
        names.push_back(name);
    if (names != speed_limiters)  // (only the loader changes the text)
        speed_limiters = names;
    v.number(turn_in_place_deg, "turn_in_place_deg", TRange::closed(0, 180, "deg"),
             "a target farther off the heading is turned to in place first (0 = off)");
    v.number(turn_rate_deg, "turn_rate_deg", TRange::closed(1, 360, "deg/s"),
             "of that turn");
    v.number(start_turn_deg, "start_turn_deg", TRange::closed(0, 180, "deg"),
             "a standing robot's aim farther off its heading is turned to first (0 = "
             "off)");
    v.number(unstick_time, "unstick_time", TRange::closed(0, 1e5, "s"),
             "a robot that has not moved for this long is turned (0 = off, else >= 2)");
    v.number(unstick_heading_deg, "unstick_heading_deg", TRange::closed(1, 180, "deg"),
             "toward its target when that is more than this off its heading");
    v.number(guide_lookahead, "guide_lookahead", TRange::closed(0, 20, "m"),
             "MRPT steers to the point this far ahead on a limiter's way (0 = off)");
    v.number(plan_follow_after, "plan_follow_after", TRange::closed(0, 1e5, "s"),
             "no progress along the global plan for this long: follow it itself (0 = "
             "off, else >= 2)");
    v.number(plan_follow_speed, "plan_follow_speed", TRange::closed(0.02, 2, "m/s"),
             "at up to this speed");
    v.number(plan_follow_distance, "plan_follow_distance", TRange::closed(0.1, 100, "m"),
             "for this far, then MRPT steers again");
    v.number(plan_follow_margin, "plan_follow_margin", TRange::closed(0, 1, "m"),
             "a sensed point may come this far inside MRPT's shape meanwhile");
    v.number(
        final_approach_speed, "final_approach_speed", TRange::closed(0, 2, "m/s"),
        "the route's end inside MRPT's shape is driven to straight at this (0 = off)");
}

void CRiskAwareReactiveNav::TOptions::validateRules() const {
    checkRule(speed_limiters.size() <= 16, section, "speed_limiters",
              std::to_string(speed_limiters.size()) + " names", "at most 16 limiters");
    // one instance per class: both would read one section, and a repeated
    // name is a typo, not a second limiter
    for (size_t i = 0; i < speed_limiters.size(); i++)
        for (size_t j = 0; j < i; j++)
            if (shortClassName(speed_limiters[i]) == shortClassName(speed_limiters[j])) {
                std::string list;
                for (const auto& n : speed_limiters)
                    list += (list.empty() ? "" : " ") + n;
                checkRule(false, section, "speed_limiters", list,
                          shortClassName(speed_limiters[i]) + " is listed twice");
            }
    // below 2 s a robot driving 0.25 m/s (5 cm a 0.2 s cycle) would count as stuck
    checkRule(unstick_time == 0 || unstick_time >= 2, section, "unstick_time",
              numberText(unstick_time), "must be 0 (off) or at least 2 s");
    checkRule(plan_follow_after == 0 || plan_follow_after >= 2, section,
              "plan_follow_after", numberText(plan_follow_after),
              "must be 0 (off) or at least 2 s");
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
    riskOptions.speed_limiters.clear();  // a config without the key: none
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

}  // namespace risknav::nav
