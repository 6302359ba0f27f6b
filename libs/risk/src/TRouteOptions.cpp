#include <risknav/common/config_read.h>
#include <risknav/risk/TRouteOptions.h>

using namespace risknav::common;

namespace risknav::risk {
void TRouteOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                       const std::string& s) {
    section = s;
    name = readString(c, s, "name", s);
    waypoints = readNumbers(c, s, "waypoints", waypoints, {}, 0, 2);
}

void TRouteOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                     const std::string& s) const {
    writeKey(c, s, "name", name);
    writeKey(c, s, "waypoints", waypoints);
}

void TRouteOptions::validate() const {
    checkRule(!name.empty(), section, "name", name, "must not be empty");
    std::string text;
    for (double v : waypoints)
        text += (text.empty() ? "" : " ") + numberText(v);
    // no waypoints was silently the straight line from start to goal
    checkRule(!waypoints.empty(), section, "waypoints", text,
              "required: x y pairs [m] (the straight line: the start and the goal)");
    checkRule(waypoints.size() % 2 == 0, section, "waypoints", text,
              "needs x y pairs [m]");
    checkKey(section, "waypoints", waypoints, TRange::any("m"));
}

}  // namespace risknav::risk
