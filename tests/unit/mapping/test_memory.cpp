// The coarse free-space memory of risknav-explore (beyond Miura et al.: it
// ranks the ways on to a destination outside the 10 m local map).
#include <risknav/mapping/CFreeSpaceMemory.h>

#include <gtest/gtest.h>

#include "free_space_fixtures.h"

#include <cmath>
#include <stdexcept>

using risknav::mapping::CFreeSpaceMemory;
using risknav::mapping::TFreeSpaceMap;
using risknav::mapping::TFusedCell;
using TState = CFreeSpaceMemory::TState;
using risknav::test::fillRect;
using risknav::test::localMap;

namespace {
/** A closed 4 x 4 m room, x in [2, 6], y in [-2, 2], walls 0.2 m, seen from
 * inside; `door`: a 1.2 m gap in its east wall. Outside it: unknown. */
TFreeSpaceMap roomSeen(bool door) {
    auto m = localMap(4.0, 0.0, 5.0, TFusedCell::Undecided);
    fillRect(m, 2.0, -2.0, 6.0, 2.0, TFusedCell::Obstacle);
    fillRect(m, 2.2, -1.8, 5.8, 1.8, TFusedCell::Free);
    if (door)
        fillRect(m, 5.8, -0.6, 6.0, 0.6, TFusedCell::Free);
    return m;
}
}  // namespace

TEST(FreeSpaceMemory, RemembersWhatScrolledOutOfTheLocalMap) {
    CFreeSpaceMemory mem(20.0, 0.25, 0.0, 0.0);
    auto a = localMap(0, 0, 4.0, TFusedCell::Free);
    fillRect(a, 1.0, -2, 1.2, 2, TFusedCell::Obstacle);
    mem.update(a);
    // the robot moved on: a window that no longer holds the wall
    mem.update(localMap(-6, 0, 4.0, TFusedCell::Free));
    EXPECT_EQ(mem.at(1.1, 0.0), TState::Obstacle);
    EXPECT_EQ(mem.at(0.0, 0.0), TState::Free);
    EXPECT_EQ(mem.at(-6.0, 0.0), TState::Free);
    EXPECT_EQ(mem.at(5.0, 5.0), TState::Unknown);
    // undecided in a later window leaves the memory as it was
    mem.update(localMap(0, 0, 4.0, TFusedCell::Undecided));
    EXPECT_EQ(mem.at(1.1, 0.0), TState::Obstacle);
    EXPECT_EQ(mem.at(0.0, 0.0), TState::Free);
    // an obstacle seen free again (a person gone) is free
    mem.update(localMap(0, 0, 4.0, TFusedCell::Free));
    EXPECT_EQ(mem.at(1.1, 0.0), TState::Free);
}

TEST(FreeSpaceMemory, AWallOnTheWindowsEdgeIsKept) {
    // memory cells [1.9, 2.15) x ...: the window [-2, 2) covers 40 % of them
    CFreeSpaceMemory mem(20.0, 0.25, -0.1, -0.1);
    auto a = localMap(0, 0, 4.0, TFusedCell::Free);
    fillRect(a, 1.95, -2, 2.0, 2, TFusedCell::Obstacle);  // its last column
    mem.update(a);
    EXPECT_EQ(mem.at(2.0, 0.0), TState::Obstacle);
    // free is taken only from cells the window covers at least half of
    mem.update(localMap(0, 0, 4.0, TFusedCell::Free));
    EXPECT_EQ(mem.at(2.0, 0.0), TState::Obstacle);
    EXPECT_EQ(mem.at(1.8, 0.0), TState::Free);
}

TEST(FreeSpaceMemory, CostOnCountsRememberedFreeOnceAndUnknownByItsWeight) {
    CFreeSpaceMemory mem(30.0, 0.25, 0.0, 0.0);
    mem.update(localMap(0, 0, 4.0, TFusedCell::Free));  // [-2, 2) remembered free
    const auto window = localMap(-4, 0, 4.0, TFusedCell::Free);  // [-6, -2) now
    mem.update(window);
    mem.computeCostToGoal({6.0, 0.0}, 2.0, window, 0.25);
    // from the window's east edge: 4 m remembered free + 4 m unknown x 2
    EXPECT_NEAR(mem.costToGoal(-2.05, 0.0, 0.1), 4.0 + 8.0, 0.5);
    // the same with the unknown weighted 1: the straight line
    mem.computeCostToGoal({6.0, 0.0}, 1.0, window, 0.25);
    EXPECT_NEAR(mem.costToGoal(-2.05, 0.0, 0.1), 8.0, 0.5);
    // deep inside the window the way on is the local planner's: none here
    EXPECT_TRUE(std::isinf(mem.costToGoal(-4.0, 0.0, 0.3)));
    // outside the memory: the weighted straight line
    EXPECT_NEAR(mem.costToGoal(40.0, 0.0, 0.3), 34.0, 1e-9);
}

TEST(FreeSpaceMemory, AClosedRoomHasNoWayOnAndADoorOpensIt) {
    CFreeSpaceMemory mem(30.0, 0.25, 0.0, 0.0);
    mem.update(roomSeen(false));
    const auto window = localMap(-4, 0, 4.0, TFusedCell::Free);  // elsewhere
    mem.computeCostToGoal({10.0, 0.0}, 2.0, window, 0.25);
    EXPECT_TRUE(std::isinf(mem.costToGoal(4.0, 0.0, 0.0)));
    EXPECT_TRUE(std::isinf(mem.costToGoal(5.5, 1.5, 0.3)));
    // the same room with a 1.2 m door east: 2 m to the door, 4 m unknown x 2
    mem.update(roomSeen(true));
    mem.computeCostToGoal({10.0, 0.0}, 2.0, window, 0.25);
    EXPECT_NEAR(mem.costToGoal(4.0, 0.0, 0.0), 2.0 + 8.0, 0.6);
    // a gap no wider than the robot (0.5 m) is no way on, though two whole
    // memory cells of it are free
    CFreeSpaceMemory narrow(30.0, 0.25, 0.0, 0.0);
    auto slit = roomSeen(false);
    fillRect(slit, 5.8, -0.26, 6.0, 0.26, TFusedCell::Free);
    narrow.update(slit);
    narrow.computeCostToGoal({10.0, 0.0}, 2.0, window, 0.25);
    EXPECT_TRUE(std::isinf(narrow.costToGoal(4.0, 0.0, 0.0)));
}

TEST(FreeSpaceMemory, BadSizesAreRefused) {
    EXPECT_THROW(CFreeSpaceMemory(0, 0.25, 0, 0), std::invalid_argument);
    EXPECT_THROW(CFreeSpaceMemory(10, 0, 0, 0), std::invalid_argument);
    EXPECT_THROW(CFreeSpaceMemory(10, -1, 0, 0), std::invalid_argument);
    EXPECT_THROW(CFreeSpaceMemory(1e6, 0.05, 0, 0), std::invalid_argument);
    EXPECT_THROW(CFreeSpaceMemory(std::nan(""), 0.25, 0, 0), std::invalid_argument);
}
