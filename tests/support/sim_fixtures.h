#pragma once
// Worlds for the unit tests of libs/sim (header only: the test executables
// that include it link risknav::sim).
#include <mrpt/maps/COccupancyGridMap2D.h>

namespace risknav::test {
// An empty 20 x 20 m room (the outside counts as walls).
inline mrpt::maps::COccupancyGridMap2D emptyRoom() {
    mrpt::maps::COccupancyGridMap2D g(-10, 10, -10, 10, 0.05f);
    g.fill(1.0f);
    return g;
}
}  // namespace risknav::test
