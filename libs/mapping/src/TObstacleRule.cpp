#include <risknav/common/config_read.h>
#include <risknav/mapping/TObstacleRule.h>

using namespace risknav::common;

namespace risknav::mapping {
void TObstacleRule::declare(Visitor& v) {
    v.number(occupied_threshold, "occupied_threshold", TRange::closed(0.01, 1),
             "occupancy (1 - P(free)) >= this: obstacle");
    v.number(free_threshold, "free_threshold", TRange::closed(0, 0.99),
             "occupancy <= this: free (< occupied_threshold); between: unknown");
    v.flag(unknown_is_obstacle, "unknown_is_obstacle",
           "unknown cells are walls for the sensors and the collisions");
    v.flag(outside_is_obstacle, "outside_is_obstacle",
           "the cells just off the map are walls for the sensors and the collisions");
}

void TObstacleRule::validateRules() const {
    checkRule(free_threshold < occupied_threshold, section, "free_threshold",
              numberText(free_threshold), "must be < occupied_threshold");
}

}  // namespace risknav::mapping
