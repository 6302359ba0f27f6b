#include <risknav/common/config_read.h>
#include <risknav/risk/TRouteOptions.h>

using namespace risknav::common;

namespace risknav::risk {
void TRouteOptions::declare(Visitor& v) {
    v.text(name, "name", true, "unique among the routes; default: the section name");
    // required, but by validateRules(): its message says what none would be
    v.numbers(waypoints, "waypoints", TRange::any("m"),
              "x y pairs, each on the map; required", TCount{0, 2});
}

void TRouteOptions::validateRules() const {
    // no waypoints was silently the straight line from start to goal
    checkRule(!waypoints.empty(), section, "waypoints", "",
              "required: x y pairs [m] (the straight line: the start and the goal)");
}

void TRouteOptions::onLoaded() {
    if (name.empty())
        name = section;
}

}  // namespace risknav::risk
