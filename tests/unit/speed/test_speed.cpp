// M1 speed control (Miura et al. 2006, sections 3-5).
#include <risknav/mapping/CFreeSpaceMemory.h>
#include <risknav/speed/CAdaptiveSpeedController.h>
#include <risknav/speed/CAdaptiveSpeedPipeline.h>
#include <risknav/speed/CExplorer.h>
#include <risknav/speed/speed_rules.h>

#include <gtest/gtest.h>

#include "free_space_fixtures.h"

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <random>
#include <thread>

using namespace risknav::speed;
using mrpt::math::TPoint2D;
using risknav::mapping::TFreeSpaceMap;
using risknav::mapping::TFusedCell;

namespace {
/** n x n cells of 5 cm centred on the origin, all free. */
TFreeSpaceMap openMap(int n = 200) {
    return risknav::test::localMap(0, 0, n * 0.05, TFusedCell::Free);
}
using risknav::test::fillRect;
/** A wall across the whole map at x in [0, 0.1] with a gap of `gap` m
 * centred on y = 0. */
TFreeSpaceMap wallWithGap(double gap) {
    auto m = openMap();
    fillRect(m, 0.0, -10, 0.1, -gap / 2, TFusedCell::Obstacle);
    fillRect(m, 0.0, gap / 2, 0.1, 10, TFusedCell::Obstacle);
    return m;
}
}  // namespace

TEST(GapRule, PaperFig12SlowAndMediumPassFastCannot) {
    // fast detours (complete planner): its cost-to-go jumps; medium owns the path
    EXPECT_EQ(safeSpeedsByGap({14.0, 10.0, 10.1}, 1.0), (std::vector<size_t>{1, 2}));
    // fast stops short of the passage (the paper's planner): path 4 m + 6 m left
    EXPECT_EQ(safeSpeedsByGap({4.0 + 6.0 + 3.0, 10.0, 10.1}, 1.0),
              (std::vector<size_t>{1, 2}));
    // no jump: all safe
    EXPECT_EQ(safeSpeedsByGap({10.2, 10.1, 10.0, 10.0}, 1.0),
              (std::vector<size_t>{0, 1, 2, 3}));
    // the first jump from below splits: two jumps, only the lowest group is safe
    EXPECT_EQ(safeSpeedsByGap({30.0, 20.0, 10.0, 10.2}, 1.0),
              (std::vector<size_t>{2, 3}));
    // no path at all for the fast ones
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(safeSpeedsByGap({inf, inf, 10.0, 10.0}, 1.0), (std::vector<size_t>{2, 3}));
    EXPECT_EQ(safeSpeedsByGap({inf, inf}, 1.0), (std::vector<size_t>{0, 1}));
    // equal to the threshold is not a jump
    EXPECT_EQ(safeSpeedsByGap({11.0, 10.0}, 1.0), (std::vector<size_t>{0, 1}));
}

TEST(UndecidedRule, DOverVTAtLeastN) {
    // N = 5, T = 0.3: at 1.1 m/s the region must be >= 1.65 m away
    EXPECT_TRUE(undecidedRuleHolds(1.65, 1.1, 0.3, 5));
    EXPECT_FALSE(undecidedRuleHolds(1.64, 1.1, 0.3, 5));
    EXPECT_TRUE(undecidedRuleHolds(0.3, 0.2, 0.3, 5));
    EXPECT_FALSE(undecidedRuleHolds(0.29, 0.2, 0.3, 5));
    EXPECT_TRUE(undecidedRuleHolds(std::numeric_limits<double>::infinity(), 1.1, 0.3, 5));
}

TEST(GridPathPlanner, AStarLengthEqualsDijkstraOnRandomMaps) {
    std::mt19937 rng(3);
    const CGridPathPlanner planner;
    for (int trial = 0; trial < 20; trial++) {
        auto m = openMap(40);
        std::uniform_real_distribution<double> u(-0.9, 0.9);
        for (int b = 0; b < 12; b++) {
            const double x = u(rng), y = u(rng);
            fillRect(m, x, y, x + 0.2, y + 0.05, TFusedCell::Obstacle);
        }
        const auto f = computePlanningField(m);
        const TPoint2D s(-0.875, -0.875), g(0.875, 0.875);
        const double infl = 0.06;
        const auto p = planner.plan(f, s, g, infl, 0.0, false);
        // Dijkstra over the same cells and moves
        const int n = m.size;
        std::vector<double> dist(size_t(n) * n, 1e18);
        using E = std::pair<double, int>;
        std::priority_queue<E, std::vector<E>, std::greater<>> q;
        const int si = m.x2idx(s.x), sj = m.y2idx(s.y), gi = m.x2idx(g.x),
                  gj = m.y2idx(g.y);
        dist[m.index(si, sj)] = 0;
        q.push({0, int(m.index(si, sj))});
        while (!q.empty()) {
            auto [dd, k] = q.top();
            q.pop();
            if (dd > dist[size_t(k)])
                continue;
            const int i = k % n, j = k / n;
            for (int dj = -1; dj <= 1; dj++)
                for (int di = -1; di <= 1; di++) {
                    if ((!di && !dj) || !m.inside(i + di, j + dj))
                        continue;
                    const size_t nk = m.index(i + di, j + dj);
                    if (f.clearance[nk] < infl)
                        continue;
                    const double nd =
                        dd + (di && dj ? std::sqrt(2.0) : 1.0) * m.resolution;
                    if (nd < dist[nk]) {
                        dist[nk] = nd;
                        q.push({nd, int(nk)});
                    }
                }
        }
        const double best = dist[m.index(gi, gj)];
        if (best > 1e17) {
            EXPECT_FALSE(p.reached) << trial;
            continue;
        }
        ASSERT_TRUE(p.reached) << trial;
        // the planner's ends are the exact start/goal points, not cell centres
        EXPECT_NEAR(p.length, best, 1e-6) << trial;
        for (const auto& pt : p.points)
            EXPECT_GE(f.clearanceAt(pt.x, pt.y), infl - 1e-9);
    }
}

TEST(SpeedController, ANarrowPassageForTheSlowestTwoPicksTheSecondSlowest) {
    // 0.8 m gap, robot radius 0.25: inflations 0.55 / 0.45 / 0.35 / 0.30;
    // only the last two fit (0.4 m half-gap). Known free map: no undecided.
    const auto f = computePlanningField(wallWithGap(0.8));
    TSpeedControlOptions o;
    const CAdaptiveSpeedController c(o, 0.25, 5);
    // just before the gap: only the slow group, and speed 2 owns the path
    auto d = c.decide(f, mrpt::math::TPose2D(-0.4, 0.0, 0), TPoint2D(2.0, 0.0));
    EXPECT_FALSE(d.temporaryTarget);
    EXPECT_EQ(d.safeByGap, (std::vector<size_t>{2, 3}));
    EXPECT_EQ(d.speedIndex, 2);
    EXPECT_EQ(d.reason, TSpeedReason::Narrow);
    EXPECT_TRUE(d.perSpeed[2].reached);
    EXPECT_FALSE(d.perSpeed[0].reached);  // the wall spans the map: no detour
    // 3 m before it, the fast speed keeps its margin for the next two cycles
    // on that path (section 4.2) and may go fast for now
    d = c.decide(f, mrpt::math::TPose2D(-3.0, 0.0, 0), TPoint2D(2.0, 0.0));
    EXPECT_EQ(d.pathIndex, 2);
    EXPECT_EQ(d.speedIndex, 0);
    // a wide gap: no narrow passage at all
    const auto wide = computePlanningField(wallWithGap(2.0));
    d = c.decide(wide, mrpt::math::TPose2D(-0.4, 0.0, 0), TPoint2D(2.0, 0.0));
    EXPECT_EQ(d.safeByGap.size(), 4u);
    EXPECT_EQ(d.speedIndex, 0);
    EXPECT_EQ(d.reason, TSpeedReason::None);
}

TEST(SpeedController, UndecidedRegionAheadLimitsTheSpeedAndTheTargetIsOnItsBoundary) {
    // the world beyond x = 1 is unknown; the goal lies in it
    auto m = openMap();
    fillRect(m, 1.0, -10, 10, 10, TFusedCell::Undecided);
    const auto f = computePlanningField(m);
    const CAdaptiveSpeedController c(TSpeedControlOptions{}, 0.25, 5);
    for (const double x0 : {-3.5, -2.0, -0.5, 0.2}) {
        const auto d = c.decide(f, mrpt::math::TPose2D(x0, 0.0, 0), TPoint2D(4.0, 0.0));
        EXPECT_TRUE(d.temporaryTarget);
        EXPECT_NEAR(d.target.y, 0.0, 0.06);
        // kept off the unknown by the slowest inflation (0.30), near it
        EXPECT_LE(d.target.x, 1.0 - 0.30);
        EXPECT_GE(d.target.x, 1.0 - 0.30 - 0.15);
        // the fastest speed whose own d (front of its margin disc at the
        // unknown) is >= N v T: d_k = x_front - x0 with x_front = 1 - r - m_k
        int expect = -1;
        for (size_t k = 0; k < 4; k++) {
            const double dk =
                std::min(1.0 - 0.25 - c.options().margins[k] - x0, d.path.length);
            if (dk >= 5 * c.options().speeds[k] * 0.3 + 0.05) {
                expect = int(k);
                break;
            }
        }
        if (expect >= 0) {
            EXPECT_EQ(d.speedIndex, expect) << x0 << " d " << d.dUndecided;
        }
        if (expect > 0) {
            EXPECT_EQ(d.reason, TSpeedReason::Undecided) << x0;
        }
    }
    // far away: fast; close: slow or stop
    EXPECT_EQ(c.decide(f, mrpt::math::TPose2D(-3.5, 0, 0), TPoint2D(4, 0)).speedIndex, 0);
    EXPECT_GE(c.decide(f, mrpt::math::TPose2D(0.0, 0, 0), TPoint2D(4, 0)).speedIndex, 2);
}

TEST(SpeedController, WalledInIsUnreachableAndStops) {
    auto m = openMap();
    fillRect(m, -1, -1, 1, -0.9, TFusedCell::Obstacle);
    fillRect(m, -1, 0.9, 1, 1, TFusedCell::Obstacle);
    fillRect(m, -1, -1, -0.9, 1, TFusedCell::Obstacle);
    fillRect(m, 0.9, -1, 1, 1, TFusedCell::Obstacle);
    const auto f = computePlanningField(m);
    const CAdaptiveSpeedController c(TSpeedControlOptions{}, 0.25, 5);
    const auto d = c.decide(f, mrpt::math::TPose2D(0, 0, 0), TPoint2D(3, 3));
    EXPECT_EQ(d.reason, TSpeedReason::Unreachable);
    EXPECT_EQ(d.speed, 0.0);
    // fixed modes stop too
    EXPECT_EQ(c.decide(f, mrpt::math::TPose2D(0, 0, 0), TPoint2D(3, 3), 0).speed, 0.0);
}

TEST(SpeedController, FixedFastBreaksItsMarginInTheNarrowPassage) {
    const auto f = computePlanningField(wallWithGap(0.8));
    const CAdaptiveSpeedController c(TSpeedControlOptions{}, 0.25, 5);
    const auto d = c.decide(f, mrpt::math::TPose2D(-0.4, 0, 0), TPoint2D(2, 0), 0);
    EXPECT_EQ(d.speed, 1.1);
    EXPECT_TRUE(d.marginBroken);
    EXPECT_TRUE(d.path.reached);
    const auto slow = c.decide(f, mrpt::math::TPose2D(-0.4, 0, 0), TPoint2D(2, 0), 3);
    EXPECT_FALSE(slow.marginBroken);
}

TEST(SpeedControlOptions, BadListsAreRefused) {
    TSpeedControlOptions o;
    o.speeds = {0.7, 1.1, 0.35, 0.2};
    EXPECT_THROW(o.validate(), std::exception);
    o = TSpeedControlOptions{};
    o.margins = {0.3, 0.2, -0.1, 0.05};
    EXPECT_THROW(o.validate(), std::exception);
    o = TSpeedControlOptions{};
    o.margins = {0.3, 0.2};
    EXPECT_THROW(o.validate(), std::exception);
    o = TSpeedControlOptions{};
    o.cycle_time = 0;
    EXPECT_THROW(o.validate(), std::exception);
    EXPECT_NO_THROW(TSpeedControlOptions{}.validate());
}

TEST(PlanningField, AHoleInAWallIsAFrontierButNoOpenOne) {
    // a wall at x in [0, 0.1] across the map with one undecided cell in it
    auto m = wallWithGap(0.0);
    fillRect(m, 0.0, -0.03, 0.1, 0.0, TFusedCell::Undecided);  // one row of cells
    fillRect(m, 0.15, -10, 10, 10, TFusedCell::Undecided);     // unknown beyond
    auto f = computePlanningField(m, 0.25);
    const size_t k = f.map.index(f.map.x2idx(-0.3), f.map.y2idx(0.0));
    EXPECT_GT(f.wayOnDist()[k], 4.0);  // no way on through it (only the map's edge)
    // without the opening test it would be one
    EXPECT_LT(computePlanningField(m, 0.0).wayOnDist()[k], 0.3);
    // a 1 m undecided stretch of the wall: room for the robot beyond it
    m = wallWithGap(0.0);
    fillRect(m, 0.0, -0.5, 0.1, 0.5, TFusedCell::Undecided);
    fillRect(m, 0.15, -10, 10, 10, TFusedCell::Undecided);
    f = computePlanningField(m, 0.25);
    EXPECT_LT(f.wayOnDist()[k], 0.3);
}

TEST(PlanningField, FreeCellsOnTheMapsEdgeAreTheWayOnWhereTheMapEnds) {
    auto m = openMap();
    fillRect(m, -10, 1.0, 10, 10, TFusedCell::Obstacle);  // a wall north
    const auto f = computePlanningField(m, 0.25);
    auto at = [&](const std::vector<float>& v, double x, double y) {
        return double(v[f.map.index(f.map.x2idx(x), f.map.y2idx(y))]);
    };
    EXPECT_LT(at(f.wayOnDist(), -4.9, 0.0), 0.1);  // west edge, open
    EXPECT_LT(at(f.wayOnDist(), 0.0, -4.9), 0.1);  // south edge
    // the edge cells under the wall's reach (< radius from it) are not open
    EXPECT_GT(at(f.wayOnDist(), -4.95, 0.9), 0.1);
    EXPECT_NEAR(at(f.wayOnDist(), 0.0, 0.0), 4.95 - 0.025, 0.03);  // only the edges
}

TEST(PlanningField, ClearanceAndWayOnDistanceEqualBruteForceOnRandomMaps) {
    // The field's definitions cell by cell, by brute force: clearance to the
    // nearest non-free cell or the ring outside the grid, the ways on
    // (frontier cells and free ring cells at least minOpening from every
    // obstacle cell) and the distance to them, each as centre to near edge
    // of the sqrtf of the exact squared centre distance.
    std::mt19937 rng(7);
    for (int trial = 0; trial < 12; trial++) {
        const int n = 24 + trial;
        auto m = risknav::test::localMap(0, 0, n * 0.05, TFusedCell::Free);
        std::uniform_int_distribution<int> cell(0, 99);
        const int pObst = 4 + 3 * (trial % 4), pUnd = 10 + 5 * (trial % 3);
        for (auto& c : m.cells) {
            const int r = cell(rng);
            c = r < pObst ? TFusedCell::Obstacle
                          : (r < pObst + pUnd ? TFusedCell::Undecided : TFusedCell::Free);
        }
        const double minOpening = trial % 3 == 0 ? 0.0 : 0.1 + 0.05 * (trial % 4);
        const auto f = computePlanningField(m, minOpening);
        const double reach = 0.1 + 0.15 * (trial % 3);
        const auto reached = computePlanningField(m, minOpening, reach);
        // the clearance computed only as far as its own reach
        const double clearReach = 0.05 + 0.1 * (trial % 4);
        const auto cleared = computePlanningField(
            m, minOpening, std::numeric_limits<double>::infinity(), clearReach);
        auto measured = [&](long d2) {
            return float(std::max(0.0, (double(std::sqrt(float(d2))) - 0.5) * 0.05));
        };
        auto at = [&](int i, int j) { return m.cells[m.index(i, j)]; };
        std::vector<std::pair<int, int>> wayOn;
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                bool way = false;
                if (at(i, j) == TFusedCell::Undecided)
                    for (const auto& [di, dj] :
                         {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
                        way = way || (m.inside(i + di, j + dj) &&
                                      at(i + di, j + dj) == TFusedCell::Free);
                const bool ring = (i == 0 || j == 0 || i == n - 1 || j == n - 1) &&
                                  at(i, j) == TFusedCell::Free;
                if (!way && !ring)
                    continue;
                bool near = false;
                for (int b = 0; b < n && minOpening > 0; b++)
                    for (int a = 0; a < n; a++)
                        near = near || (at(a, b) == TFusedCell::Obstacle &&
                                        measured(long(a - i) * (a - i) +
                                                 long(b - j) * (b - j)) < minOpening);
                if (!near)
                    wayOn.emplace_back(i, j);
            }
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                const size_t k = m.index(i, j);
                // clearance: the ring outside the grid is a source
                long best = std::min({long(i + 1) * (i + 1), long(n - i) * (n - i),
                                      long(j + 1) * (j + 1), long(n - j) * (n - j)});
                for (int b = 0; b < n; b++)
                    for (int a = 0; a < n; a++)
                        if (at(a, b) != TFusedCell::Free)
                            best = std::min(
                                best, long(a - i) * (a - i) + long(b - j) * (b - j));
                ASSERT_EQ(f.clearance[k], measured(best))
                    << trial << " " << i << " " << j;
                long bestWay = -1;
                for (const auto& [a, b] : wayOn) {
                    const long d2 = long(a - i) * (a - i) + long(b - j) * (b - j);
                    if (bestWay < 0 || d2 < bestWay)
                        bestWay = d2;
                }
                if (bestWay < 0)
                    ASSERT_TRUE(std::isinf(f.wayOnDist()[k]));
                else
                    ASSERT_EQ(f.wayOnDist()[k], measured(bestWay))
                        << trial << " " << i << " " << j;
                // computed only as far as a reach: the same up to it, and
                // beyond it nothing that would pass a test against it
                const float r = reached.wayOnDist()[k];
                if (f.wayOnDist()[k] <= reach)
                    ASSERT_EQ(r, f.wayOnDist()[k]) << trial << " " << i << " " << j;
                else
                    ASSERT_TRUE(r > reach) << trial << " " << i << " " << j;
                const float c = cleared.clearance[k];
                if (f.clearance[k] <= clearReach)
                    ASSERT_EQ(c, f.clearance[k]) << trial << " " << i << " " << j;
                else
                    ASSERT_TRUE(c > clearReach) << trial << " " << i << " " << j;
            }
        EXPECT_EQ(reached.clearance, f.clearance);
        EXPECT_EQ(cleared.wayOnDist(), f.wayOnDist());
        // the ways on left to the first read: the same values then
        const auto lazy = computePlanningField(
            m, minOpening, reach, std::numeric_limits<double>::infinity(), {}, false);
        EXPECT_FALSE(lazy.hasWayOnDist());
        EXPECT_TRUE(reached.hasWayOnDist());
        EXPECT_EQ(lazy.clearance, f.clearance);
        EXPECT_EQ(lazy.wayOnDist(), reached.wayOnDist());
        EXPECT_TRUE(lazy.hasWayOnDist());
    }
}

TEST(PlanningField, TheControllerRefusesAFieldComputedForANarrowerBandOrClearance) {
    const CAdaptiveSpeedController ctrl(TSpeedControlOptions{}, 0.25, 5);
    const double band = ctrl.wayOnBand(0.05);
    EXPECT_DOUBLE_EQ(band, 0.25 + TSpeedControlOptions{}.margins.back() + 0.1);
    const auto m = openMap(60);
    EXPECT_NO_THROW(ctrl.decide(computePlanningField(m, 0.25, band), {0, 0, 0}, {1, 0}));
    EXPECT_THROW(
        ctrl.decide(computePlanningField(m, 0.25, band - 0.01), {0, 0, 0}, {1, 0}),
        std::invalid_argument);
    // and one whose clearance ends before the widest inflation (the
    // fastest speed's margin)
    const double widest = 0.25 + TSpeedControlOptions{}.margins.front();
    EXPECT_NO_THROW(
        ctrl.decide(computePlanningField(m, 0.25, band, widest), {0, 0, 0}, {1, 0}));
    EXPECT_THROW(ctrl.decide(computePlanningField(m, 0.25, band, widest - 0.01),
                             {0, 0, 0}, {1, 0}),
                 std::invalid_argument);
}

TEST(SpeedController, TheMemoryKeepsTheRobotOutOfAForgottenDeadEndRoom) {
    // The T junction's trap in small: east of a wall (x in [2, 2.2], door at
    // |y| < 0.5) lies a room the local map has forgotten (undecided); the
    // goal lies beyond it, 10 m east. The straight-line rule goes through the
    // door. The memory saw the room closed on every side.
    auto local = openMap();
    fillRect(local, 2.0, -10, 2.2, 10, TFusedCell::Obstacle);
    fillRect(local, 2.0, -0.5, 2.2, 0.5, TFusedCell::Free);
    fillRect(local, 2.25, -10, 10, 10, TFusedCell::Undecided);
    const auto f = computePlanningField(local, 0.25);
    const CAdaptiveSpeedController c(TSpeedControlOptions{}, 0.25, 5);
    const TPoint2D goal(10.0, 0.0);
    TPoint2D target;
    bool temporary = false;
    ASSERT_TRUE(c.chooseTarget(f, {0, 0}, goal, target, temporary));
    EXPECT_TRUE(temporary);
    EXPECT_GT(target.x, 1.4);  // at the door
    EXPECT_LT(std::abs(target.y), 0.6);

    risknav::mapping::CFreeSpaceMemory mem(40.0, 0.25, 0.0, 0.0);
    auto room = openMap(120);  // 6 m around (4, 0)
    for (auto& cell : room.cells)
        cell = TFusedCell::Undecided;
    room.xMin = 1.0;
    room.yMin = -3.0;
    fillRect(room, 2.0, -2.2, 5.2, 2.2, TFusedCell::Obstacle);
    fillRect(room, 2.2, -2.0, 5.0, 2.0, TFusedCell::Free);
    fillRect(room, 2.0, -0.5, 2.2, 0.5, TFusedCell::Free);  // the door
    mem.update(room);
    mem.computeCostToGoal(goal, 2.0, f.map, 0.25);
    TTargetHints hints;
    hints.goalCost = [&](double x, double y) { return mem.costToGoal(x, y, 0.45); };
    ASSERT_TRUE(c.chooseTarget(f, {0, 0}, goal, target, temporary, hints));
    EXPECT_TRUE(temporary);
    // the way on is where the local map ends, away from the room
    EXPECT_TRUE(target.x < 1.0 || std::abs(target.y) > 2.5)
        << target.x << " " << target.y;
    EXPECT_GT(std::max(std::abs(target.x), std::abs(target.y)), 4.5);
}

TEST(SpeedController, ASwitchCostHoldsThePreviousTemporaryDestination) {
    // two ways on: a 2 m opening north-east and one west; the goal is east
    auto m = openMap();
    fillRect(m, -10, 2.0, 10, 10, TFusedCell::Obstacle);
    fillRect(m, -10, -10, 10, -2.0, TFusedCell::Obstacle);
    fillRect(m, 3.0, -10, 10, 10, TFusedCell::Undecided);
    fillRect(m, -10, -10, -3.0, 10, TFusedCell::Undecided);
    const auto f = computePlanningField(m, 0.25);
    TSpeedControlOptions o;
    o.target_switch_cost = 0;
    const TPoint2D goal(4.0, 8.0);
    TPoint2D a, b;
    bool temporary = false;
    ASSERT_TRUE(
        CAdaptiveSpeedController(o, 0.25, 5).chooseTarget(f, {0, 0}, goal, a, temporary));
    EXPECT_GT(a.x, 2.0);  // east, nearer the goal
    TTargetHints hints;
    hints.previous = TPoint2D(-2.6, 0.0);  // last cycle it went west
    ASSERT_TRUE(CAdaptiveSpeedController(o, 0.25, 5)
                    .chooseTarget(f, {0, 0}, goal, b, temporary, hints));
    EXPECT_NEAR(b.x, a.x, 1e-9);  // no switch cost: east again
    o.target_switch_cost = 1000;
    ASSERT_TRUE(CAdaptiveSpeedController(o, 0.25, 5)
                    .chooseTarget(f, {0, 0}, goal, b, temporary, hints));
    EXPECT_LT(std::hypot(b.x + 2.6, b.y), 1.0);  // held west
}

TEST(GridPathPlanner, TheLookaheadPointIsAheadOnThePathAndKeepsItsClearance) {
    const auto m = openMap(100);  // 5 m, all free
    const auto f = computePlanningField(m);
    TPlannedPath p;
    for (int k = 0; k <= 40; k++)
        p.points.emplace_back(-2.0 + 0.05 * k, 0.0);  // 2 m east along y = 0
    // from beside the path: nearest is the foot, ahead the first >= L from there
    auto la = lookaheadPoint(p, f, {-1.5, 0.1}, 0.5);
    EXPECT_EQ(la.nearest, 10u);
    EXPECT_NEAR(p.points[la.ahead].x, -1.0, 0.051);
    // beyond the end: the last point
    EXPECT_EQ(lookaheadPoint(p, f, {-1.5, 0.0}, 10.0).ahead, 40u);
    EXPECT_EQ(lookaheadPoint(TPlannedPath{}, f, {0, 0}, 1.0).ahead, 0u);
    // Round a wall's corner: east along y = 0.8 above a wall (x in [0, 0.4],
    // top y = 0.3), then south along x = 0.8. From (-0.5, 0.8) the point
    // 1.5 m away lies down the far side, and the chord to it passes 2 cm from
    // the wall's corner (the path keeps 0.4 m): pulled back to where the
    // chord keeps the path's clearance, on the top stretch or just round.
    auto w = openMap(100);
    fillRect(w, 0.0, -10, 0.4, 0.3, TFusedCell::Obstacle);
    const auto fw = computePlanningField(w);
    TPlannedPath east;
    for (int k = 0; k <= 26; k++)
        east.points.emplace_back(-0.5 + 0.05 * k, 0.8);
    for (int k = 1; k <= 20; k++)
        east.points.emplace_back(0.8, 0.8 - 0.05 * k);
    const TPoint2D from(-0.5, 0.8);
    size_t unpulled = 0;
    while (unpulled + 1 < east.points.size() &&
           std::hypot(east.points[unpulled].x - from.x,
                      east.points[unpulled].y - from.y) < 1.5)
        unpulled++;
    ASSERT_LT(east.points[unpulled].y, 0.3);  // down the far side
    const auto la2 = lookaheadPoint(east, fw, from, 1.5);
    EXPECT_LT(la2.ahead, unpulled);
    EXPECT_GT(east.points[la2.ahead].y, 0.5);
    const auto& q = east.points[la2.ahead];
    for (int k = 1; k <= 50; k++) {  // the chord keeps >= 0.3 m
        const double t = k / 50.0;
        EXPECT_GT(
            fw.clearanceAt(from.x + t * (q.x - from.x), from.y + t * (q.y - from.y)),
            0.3);
    }
}

TEST(GridPathPlanner, TheEscapeNeverComesNearerThanTheStartUnlessThereIsNoOtherWay) {
    // a hand-made field: clearance 0.5 everywhere (>= the inflation 0.3)
    // but around the start cell (10, 10), which has 0.20
    TPlanningField f;
    f.map = openMap(20);
    f.clearance.assign(f.map.cells.size(), 0.5f);
    auto set = [&](int i, int j, float c) { f.clearance[f.map.index(i, j)] = c; };
    for (int j = 6; j <= 14; j++)
        for (int i = 6; i <= 14; i++)
            set(i, j, 0.1f);
    set(10, 10, 0.20f);
    set(11, 10, 0.19f);  // nearer than the start, within half a cell
    for (int i = 6; i <= 9; i++)
        set(i, 10, 0.21f);  // a way out west, never nearer
    CTraversable strict(f, 10, 10, 0.30, true);
    EXPECT_FALSE(strict(11, 10));
    EXPECT_TRUE(strict(9, 10));
    EXPECT_FALSE(strict(10, 11));  // 0.1: never
    // the way west closed: half a cell of rounding is the only way out
    for (int i = 6; i <= 9; i++)
        set(i, 10, 0.1f);
    for (int i = 12; i <= 14; i++)
        set(i, 10, 0.19f);
    CTraversable rounding(f, 10, 10, 0.30, true);
    EXPECT_TRUE(rounding(11, 10));
    EXPECT_FALSE(rounding(9, 10));
    // and the planner then leaves by it
    const auto p =
        CGridPathPlanner().plan(f, {f.map.idx2x(10), f.map.idx2y(10)},
                                {f.map.idx2x(18), f.map.idx2y(10)}, 0.30, 0.0, true);
    EXPECT_TRUE(p.reached);
}

TEST(StoppingRule, APostBesideTheRobotDoesNotStopItAPointAheadDoes) {
    TPlannedPath path;
    for (int k = 0; k <= 60; k++)
        path.points.emplace_back(0.05 * k, 0.0);
    path.length = 3.0;
    path.reached = true;
    risknav::common::TRobotOptions robot;  // radius 0.25
    // ahead, on the path: stop
    EXPECT_TRUE(pathBlocked(path, {{0.6, 0.1}}, 0.35, robot, 0.1, 0.0));
    // just ahead and beside: 0.22 m from the robot, 0.20 m from the path
    // ahead; within 1 cm of noise it comes nearer, within 6 cm it does not
    EXPECT_TRUE(pathBlocked(path, {{0.1, 0.2}}, 0.35, robot, 0.1, 0.0, 0.01));
    EXPECT_FALSE(pathBlocked(path, {{0.1, 0.2}}, 0.35, robot, 0.1, 0.0, 0.06));
    // behind the robot: never
    EXPECT_FALSE(pathBlocked(path, {{-0.2, 0.0}}, 0.35, robot, 0.1, 0.0));
}

TEST(AdaptiveSpeedPipeline, TakeFieldMovesTheCycleFieldOutAndDecideThenRefuses) {
    CAdaptiveSpeedPipeline::TParams p;
    p.laserModel.p_obs_given_obstacle = 0.7;
    p.laserModel.p_obs_given_free = 0.3;
    p.useRange2 = false;
    p.memorySize = 0;
    const mrpt::math::TPose2D ego(1.0, 2.0, 0.3);
    CAdaptiveSpeedPipeline pipe(p, ego);
    pipe.update(ego, nullptr, ego, nullptr, ego);
    const TPlanningField copy = pipe.field();
    ASSERT_EQ(copy.map.cells.size(), 200u * 200u);
    EXPECT_NO_THROW(pipe.decide(ego, {3.0, 2.0}, -1, std::nullopt));
    const TPlanningField taken = pipe.takeField();
    EXPECT_EQ(taken.map.cells, copy.map.cells);
    EXPECT_EQ(taken.clearance, copy.clearance);
    EXPECT_EQ(taken.wayOnDist(), copy.wayOnDist());
    EXPECT_TRUE(pipe.field().map.cells.empty());
    EXPECT_THROW(pipe.decide(ego, {3.0, 2.0}, -1, std::nullopt), std::logic_error);
    pipe.update(ego, nullptr, ego, nullptr, ego);  // the next cycle has its own
    EXPECT_EQ(pipe.field().clearance, copy.clearance);
}

namespace {
bool samePath(const TPlannedPath& a, const TPlannedPath& b) {
    if (a.points.size() != b.points.size() || a.reached != b.reached ||
        !(a.length == b.length) ||
        !(a.costToGo == b.costToGo || (std::isinf(a.costToGo) && std::isinf(b.costToGo))))
        return false;
    for (size_t k = 0; k < a.points.size(); k++)
        if (a.points[k].x != b.points[k].x || a.points[k].y != b.points[k].y)
            return false;
    return true;
}
}  // namespace

TEST(SpeedController, ItsPartsInAnyOrderOrOnThreadsGiveTheSerialDecision) {
    // decide() with a parallel executor: the per-speed plans to a temporary
    // destination as parts (to the goal they go one after the other). Each
    // scene against the serial decision, with the parts run backwards and
    // each on its own thread.
    const risknav::common::TParallelFor backwards =
        [](size_t n, const std::function<void(size_t)>& body) {
            for (size_t i = n; i-- > 0;)
                body(i);
        };
    const risknav::common::TParallelFor threads =
        [](size_t n, const std::function<void(size_t)>& body) {
            std::vector<std::thread> ts;
            for (size_t i = 0; i < n; i++)
                ts.emplace_back([&body, i] { body(i); });
            for (auto& t : ts)
                t.join();
        };
    auto unknownBeyond = openMap();
    fillRect(unknownBeyond, 1.0, -10, 10, 10, TFusedCell::Undecided);
    auto walledIn = openMap();
    fillRect(walledIn, -1, -1, 1, -0.9, TFusedCell::Obstacle);
    fillRect(walledIn, -1, 0.9, 1, 1, TFusedCell::Obstacle);
    fillRect(walledIn, -1, -1, -0.9, 1, TFusedCell::Obstacle);
    fillRect(walledIn, 0.9, -1, 1, 1, TFusedCell::Obstacle);
    struct TScene {
        TFreeSpaceMap map;
        mrpt::math::TPose2D robot;
        TPoint2D goal;
        const char* what;
    };
    const std::vector<TScene> scenes = {
        {wallWithGap(0.8), {-0.4, 0, 0}, {2.0, 0.0}, "the goal, narrow gap"},
        {wallWithGap(2.0), {-3.0, 1, 0}, {2.0, -2.0}, "the goal, wide gap"},
        {wallWithGap(0.8), {-2.0, 0, 0}, {0.2, 2.0}, "free goal by the wall"},
        {unknownBeyond, {-2.0, 0, 0}, {4.0, 0.0}, "goal in the unknown"},
        {walledIn, {0, 0, 0}, {3.0, 3.0}, "free goal walled off"},
    };
    int toTheGoal = 0, elsewhere = 0;
    for (const auto& s : scenes) {
        CAdaptiveSpeedController serial(TSpeedControlOptions{}, 0.25, 5);
        const auto field =
            computePlanningField(s.map, 0.25, serial.wayOnBand(0.05), 1.05);
        const auto expect = serial.decide(field, s.robot, s.goal);
        (!expect.temporaryTarget && !expect.nearestToGoal &&
                 expect.reason != TSpeedReason::Unreachable
             ? toTheGoal
             : elsewhere)++;
        for (const auto& exec : {backwards, threads}) {
            const auto f =
                computePlanningField(s.map, 0.25, serial.wayOnBand(0.05), 1.05, exec);
            EXPECT_EQ(f.clearance, field.clearance) << s.what;
            EXPECT_EQ(f.wayOnDist(), field.wayOnDist()) << s.what;
            CAdaptiveSpeedController c(TSpeedControlOptions{}, 0.25, 5);
            c.setParallelFor(exec);
            const auto d = c.decide(field, s.robot, s.goal);
            EXPECT_EQ(d.speedIndex, expect.speedIndex) << s.what;
            EXPECT_EQ(d.reason, expect.reason) << s.what;
            EXPECT_EQ(d.target.x, expect.target.x) << s.what;
            EXPECT_EQ(d.target.y, expect.target.y) << s.what;
            EXPECT_EQ(d.temporaryTarget, expect.temporaryTarget) << s.what;
            EXPECT_EQ(d.nearestToGoal, expect.nearestToGoal) << s.what;
            EXPECT_EQ(d.pathIndex, expect.pathIndex) << s.what;
            EXPECT_EQ(d.safeByGap, expect.safeByGap) << s.what;
            EXPECT_EQ(d.allowed, expect.allowed) << s.what;
            EXPECT_TRUE(samePath(d.path, expect.path)) << s.what;
            ASSERT_EQ(d.perSpeed.size(), expect.perSpeed.size()) << s.what;
            for (size_t k = 0; k < d.perSpeed.size(); k++)
                EXPECT_TRUE(samePath(d.perSpeed[k], expect.perSpeed[k])) << s.what << k;
        }
    }
    // plans to the goal and to other targets (the parallel ones) were made
    EXPECT_GE(toTheGoal, 2);
    EXPECT_GE(elsewhere, 2);
}

namespace {
/** CGridPathPlanner without the cost bound: the reference for it. */
class CUnboundedPlanner : public IPathPlanner {
  public:
    TPlannedPath plan(const TPlanningField& field, const TPoint2D& start,
                      const TPoint2D& goal, double inflation, double goalTolerance,
                      bool escape, double /*maxCost*/) const override {
        return m_planner.plan(field, start, goal, inflation, goalTolerance, escape);
    }
    std::string name() const override { return "unbounded"; }

  private:
    CGridPathPlanner m_planner;
};

/** A random 6 x 6 m scene: a wall across x = 0 with one or two gaps of
 * 0.5-1.3 m (only some speeds' margins pass), boxes, now and then unknown
 * space beyond some x or a wall closing a detour. */
TFreeSpaceMap randomGapScene(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    auto m = risknav::test::localMap(0, 0, 6.0, TFusedCell::Free);
    const double wallX = -0.5 + u(rng);
    fillRect(m, wallX, -3, wallX + 0.1, 3, TFusedCell::Obstacle);
    for (int g = 0, ng = u(rng) < 0.5 ? 1 : 2; g < ng; g++) {
        const double y = -2.5 + 5 * u(rng), w = 0.5 + 0.8 * u(rng);
        fillRect(m, wallX, y - w / 2, wallX + 0.1, y + w / 2, TFusedCell::Free);
    }
    for (int b = 0, nb = int(6 * u(rng)); b < nb; b++) {
        const double x = -3 + 6 * u(rng), y = -3 + 6 * u(rng);
        fillRect(m, x, y, x + 0.2 + 0.8 * u(rng), y + 0.1 + 0.3 * u(rng),
                 TFusedCell::Obstacle);
    }
    if (u(rng) < 0.25) {
        const double x = 1.0 + 1.5 * u(rng);
        fillRect(m, x, -3, 3, 3, TFusedCell::Undecided);
    }
    return m;
}
}  // namespace

TEST(GridPathPlanner, ACostBoundCutsOffOnlyPathsThatCostMore) {
    // against the unbounded search on random scenes: a plan not cut off is
    // the unbounded plan; a cut-off one is so only when the unbounded
    // cost-to-go exceeds the bound; and a bound 4 cells (and the
    // tolerance) below the cost always cuts (the bound does bound)
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(0, 1);
    const CGridPathPlanner planner;
    int cut = 0, kept = 0, tight = 0;
    for (int trial = 0; trial < 60; trial++) {
        const auto m = randomGapScene(rng);
        const auto f = computePlanningField(m, 0.25, 0.4, 1.05);
        const TPoint2D s(-2.5 + 1.5 * u(rng), -2.5 + 5 * u(rng));
        const TPoint2D g(1.0 + 1.5 * u(rng), -2.5 + 5 * u(rng));
        const double infl = 0.25 + 0.3 * u(rng), tol = u(rng) < 0.5 ? 0.0 : 0.3 * u(rng);
        const bool escape = u(rng) < 0.3;
        const TPlannedPath full = planner.plan(f, s, g, infl, tol, escape);
        EXPECT_FALSE(full.cutOff);
        const double c = full.costToGo;
        const double finite = std::isfinite(c) ? c : 6.0;
        for (const double maxCost : {0.0, finite - 1.0, finite - 0.2, finite - 0.05,
                                     finite - 0.01, finite, finite + 0.5}) {
            const TPlannedPath b = planner.plan(f, s, g, infl, tol, escape, maxCost);
            if (b.cutOff) {
                cut++;
                EXPECT_GT(c, maxCost) << trial << " " << maxCost;
                EXPECT_FALSE(b.reached);
                EXPECT_TRUE(std::isinf(b.costToGo));
            } else {
                kept++;
                EXPECT_TRUE(samePath(b, full)) << trial << " " << maxCost;
            }
        }
        if (std::isfinite(c) && c > 0.5 + 1.1 * tol) {
            // within the tolerance the path may end up to tol short of the
            // goal (the bound's slack covers 1.5 cells of ends + tol / 10)
            const TPlannedPath b =
                planner.plan(f, s, g, infl, tol, escape, c - 1.1 * tol - 0.2);
            EXPECT_TRUE(b.cutOff) << trial;
            tight++;
        }
    }
    EXPECT_GT(cut, 50);
    EXPECT_GT(kept, 50);
    EXPECT_GT(tight, 20);
}

TEST(SpeedController, TheGoalShortcutAndTheCostBoundGiveTheFullSearchesDecision) {
    // decide() takes the goal as the target when the slowest plan reaches
    // it (no flood), and bounds the faster plans by what the gap rule uses.
    // Against chooseTarget()'s flood and an unbounded planner on random
    // scenes, with gap thresholds from tight to loose: the same target and
    // decision; every cut-off plan's unbounded cost-to-go is beyond every
    // slower one's + the threshold. The last 100 scenes with random
    // candidate lists too: 1-5 speeds, margins that fall or stay equal.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    int shortcut = 0, flooded = 0, cutPlans = 0, narrow = 0;
    for (int trial = 0; trial < 250; trial++) {
        const auto m = randomGapScene(rng);
        TSpeedControlOptions o;
        o.gap_threshold = trial % 3 == 0 ? 0.3 : (trial % 3 == 1 ? 1.0 : 2.5);
        if (trial >= 150) {
            const int n = 1 + int(5 * u(rng));
            o.speeds.clear();
            o.margins.clear();
            double margin = 0.3 * u(rng);
            for (int k = 0; k < n; k++) {
                o.speeds.push_back(1.2 * (n - k) / n);
                o.margins.push_back(margin);
                if (u(rng) < 0.7)
                    margin *= u(rng);
            }
            o.gap_threshold = 0.05 + 2 * u(rng);
        }
        const CAdaptiveSpeedController c(o, 0.25, 5);
        const CAdaptiveSpeedController ref(o, 0.25, 5,
                                           std::make_shared<CUnboundedPlanner>());
        const auto f = computePlanningField(m, 0.25, c.wayOnBand(0.05), 1.05);
        const mrpt::math::TPose2D robot(-2.5 + 1.5 * u(rng), -2.5 + 5 * u(rng), 0);
        const TPoint2D goal(1.0 + 1.8 * u(rng), -2.8 + 5.6 * u(rng));
        const auto d = c.decide(f, robot, goal);
        const auto e = ref.decide(f, robot, goal);
        TPoint2D target;
        bool temporary = false;
        const bool chosen =
            c.chooseTarget(f, {robot.x, robot.y}, goal, target, temporary);
        const int gi = m.x2idx(goal.x), gj = m.y2idx(goal.y);
        const bool goalFree = m.cells[m.index(gi, gj)] == TFusedCell::Free;
        (goalFree && !temporary && target.x == goal.x && target.y == goal.y ? shortcut
                                                                            : flooded)++;
        if (!chosen) {
            EXPECT_EQ(d.reason, TSpeedReason::Unreachable) << trial;
            continue;
        }
        EXPECT_EQ(d.target.x, target.x) << trial;
        EXPECT_EQ(d.target.y, target.y) << trial;
        EXPECT_EQ(d.temporaryTarget, temporary) << trial;
        EXPECT_EQ(d.speedIndex, e.speedIndex) << trial;
        EXPECT_EQ(d.reason, e.reason) << trial;
        EXPECT_EQ(d.pathIndex, e.pathIndex) << trial;
        EXPECT_EQ(d.safeByGap, e.safeByGap) << trial;
        EXPECT_EQ(d.allowed, e.allowed) << trial;
        EXPECT_EQ(d.dUndecided, e.dUndecided) << trial;
        EXPECT_TRUE(samePath(d.path, e.path)) << trial;
        narrow += d.reason == TSpeedReason::Narrow;
        ASSERT_EQ(d.perSpeed.size(), e.perSpeed.size());
        const size_t n = d.perSpeed.size();
        for (size_t k = 0; k < n; k++) {
            if (!d.perSpeed[k].cutOff) {
                EXPECT_TRUE(samePath(d.perSpeed[k], e.perSpeed[k])) << trial << " " << k;
                continue;
            }
            cutPlans++;
            double slower = 0;  // the slower plans it was bounded by
            for (size_t j = k + 1; j < n; j++)
                if (!d.perSpeed[j].cutOff)
                    slower = std::max(slower, e.perSpeed[j].costToGo);
            EXPECT_GT(e.perSpeed[k].costToGo, slower + o.gap_threshold)
                << trial << " " << k;
        }
    }
    EXPECT_GT(shortcut, 30);
    EXPECT_GT(flooded, 20);
    EXPECT_GT(cutPlans, 30);
    EXPECT_GT(narrow, 20);
    // a robot by a wall (inside the slowest margin) and a free goal a cell
    // or two along it: the slowest plan reaches the goal by the escape, but
    // the goal lacks the margin, so the flood's answer is not the goal
    const auto m = wallWithGap(0.8);
    const CAdaptiveSpeedController c(TSpeedControlOptions{}, 0.25, 5);
    const auto f = computePlanningField(m, 0.25, c.wayOnBand(0.05), 1.05);
    int escapedToTheGoal = 0;
    for (int k = 0; k <= 3; k++) {
        const mrpt::math::TPose2D robot(-0.225, 1.0, 0);
        const TPoint2D goal(-0.225 - 0.01 * k, 1.0 + 0.05 * k);
        escapedToTheGoal += CGridPathPlanner()
                                .plan(f, {robot.x, robot.y}, goal, 0.3, 0.0, true)
                                .reached &&
                            f.clearanceAt(goal.x, goal.y) < 0.3;
        TPoint2D target;
        bool temporary = false;
        ASSERT_TRUE(c.chooseTarget(f, {robot.x, robot.y}, goal, target, temporary));
        const auto d = c.decide(f, robot, goal);
        EXPECT_EQ(d.target.x, target.x) << k;
        EXPECT_EQ(d.target.y, target.y) << k;
        EXPECT_EQ(d.temporaryTarget, temporary) << k;
    }
    EXPECT_GE(escapedToTheGoal, 2);
}

// risknav-explore judges "reached" on the true pose: a belief that says
// arrived where the truth is 1 m off is a localization error, not reached.
TEST(ExploreArrival, ABeliefAtTheDestinationWithTheTruth1mOffIsNotReached) {
    using mrpt::math::TPoint2D;
    using mrpt::math::TPose2D;
    const TPoint2D dest(5, 2);
    // the belief 0.1 m from the destination, the truth 1 m from it
    const TPose2D believed(5.1, 2, 0), truth(5, 3, 0);
    const auto a = judgeArrival(dest, truth, believed, 0.3);
    EXPECT_FALSE(a.reached);
    EXPECT_STREQ(a.status, "localization_error");
    EXPECT_NEAR(a.trueError, 1.0, 1e-12);
    EXPECT_NEAR(a.beliefError, std::hypot(0.1, 1.0), 1e-12);
    EXPECT_NEAR(a.believedDistance, 0.1, 1e-12);
    EXPECT_DOUBLE_EQ(a.allowed, 0.3);
    // the truth within the tolerance: reached, whatever the belief's error
    const auto b = judgeArrival(dest, TPose2D(5, 2.25, 1), believed, 0.3);
    EXPECT_TRUE(b.reached);
    EXPECT_STREQ(b.status, "reached");
    EXPECT_NEAR(b.beliefError, std::hypot(0.1, 0.25), 1e-12);
    // exactly at the tolerance is out of it (as the robot's own rule)
    EXPECT_FALSE(
        judgeArrival(TPoint2D(0, 0), TPose2D(0.25, 0, 0), TPose2D(), 0.25).reached);
    // a perfect belief: the truth is where the belief is
    const auto c = judgeArrival(dest, believed, believed, 0.3);
    EXPECT_TRUE(c.reached);
    EXPECT_EQ(c.beliefError, 0.0);
}

// A destination nearer an obstacle than the robot may come: reached within
// tolerance / 2 of the nearest point the robot may truly come to; a robot
// that halted short of that in its own belief "fell_short".
TEST(ExploreArrival, ADestinationByAWallCountsAtTheNearestPointTheRobotMayCome) {
    using mrpt::math::TPoint2D;
    using mrpt::math::TPose2D;
    const TPoint2D dest(0, 0);
    // it may come to 0.25 m: allowed 0.25 + 0.15 = 0.40 m
    const auto a =
        judgeArrival(dest, TPose2D(0.38, 0, 0), TPose2D(0.38, 0, 0), 0.3, 0.25);
    EXPECT_TRUE(a.reached);
    EXPECT_DOUBLE_EQ(a.allowed, 0.4);
    // 0.5 m away in truth and in belief: the robot knew it was short
    const auto b = judgeArrival(dest, TPose2D(0.5, 0, 0), TPose2D(0.5, 0, 0), 0.3, 0.25);
    EXPECT_FALSE(b.reached);
    EXPECT_STREQ(b.status, "fell_short");
    // 0.5 m away in truth, the belief at 0.3 m: the belief's error (0.2 m)
    // is at least the miss (0.1 m)
    const auto c = judgeArrival(dest, TPose2D(0.5, 0, 0), TPose2D(0.3, 0, 0), 0.3, 0.25);
    EXPECT_STREQ(c.status, "localization_error");
    // the belief 0.05 m off, the miss 0.1 m: its own map held it short
    EXPECT_STREQ(
        judgeArrival(dest, TPose2D(0.5, 0, 0), TPose2D(0.45, 0, 0), 0.3, 0.25).status,
        "fell_short");
    // a destination in the open whose belief arrived at its nearest point
    // 0.6 m off in belief, the truth 0.5 m away: the belief's
    EXPECT_STREQ(
        judgeArrival(dest, TPose2D(0.5, 0, 0), TPose2D(-0.1, 0.6, 0), 0.3).status,
        "localization_error");
    // a negative nearest distance is none
    EXPECT_DOUBLE_EQ(judgeArrival(dest, TPose2D(), TPose2D(), 0.3, -1).allowed, 0.3);
}

// A memory smaller than the run (risknav-explore's 50 m on maps of 50-150 m)
// ends between the robot and its destination: where the local map reaches
// its edge, the border cells are closed (the local map's free cells, or
// grown by the radius from a wall), the way on across the edge costs +inf,
// and the robot took a side room instead (and back, as the local map
// changed) until the not-approaching alarm gave the destination up.
TEST(ExploreMemory, CoversEveryDestinationSoTheWayOnAtItsEdgeStaysOpen) {
    // the configured side grows to hold every destination with a local map
    // to spare; 0 (no memory) stays 0; a larger one is kept
    EXPECT_DOUBLE_EQ(exploreMemorySize(50, 0.25, 10, {0, 0}, {40, 0, -5, 3}), 100);
    EXPECT_DOUBLE_EQ(exploreMemorySize(0, 0.25, 10, {0, 0}, {40, 0}), 0);
    EXPECT_DOUBLE_EQ(exploreMemorySize(300, 0.25, 10, {0, 0}, {40, 0}), 300);
    EXPECT_DOUBLE_EQ(exploreMemorySize(50, 0.25, 10, {0, 0}, {4000, 0}), 4095 * 0.25);
    CExplorer ex;
    ex.explore.start = {1.0, 2.0, 0.0};
    ex.explore.destinations = {41.0, 2.0};
    ex.explore.memory_size = 50;
    EXPECT_DOUBLE_EQ(ex.pipelineParams().memorySize, 100);

    // the local map: a corridor 1.2 m wide along y = 0 from the robot at
    // x = 20 east to the map's edge at x = 25, and a side room to the north,
    // open to the unknown; the goal lies 20 m further east
    auto local = risknav::test::localMap(20, 0, 10.0, TFusedCell::Obstacle);
    fillRect(local, 15.0, -0.6, 25.0, 0.6, TFusedCell::Free);
    fillRect(local, 19.0, 0.4, 21.0, 3.0, TFusedCell::Free);
    fillRect(local, 19.0, 3.0, 21.0, 5.0, TFusedCell::Undecided);
    const auto f = computePlanningField(local, 0.25);
    const CAdaptiveSpeedController c(TSpeedControlOptions{}, 0.25, 5);
    const TPoint2D goal(45.0, 0.0);
    auto choose = [&](double memorySide) {
        risknav::mapping::CFreeSpaceMemory mem(memorySide, 0.25, 0.0, 0.0);
        mem.update(local);
        mem.computeCostToGoal(goal, 2.0, f.map, 0.25);
        TTargetHints hints;
        hints.goalCost = [&](double x, double y) { return mem.costToGoal(x, y, 0.45); };
        TPoint2D target;
        bool temporary = false;
        EXPECT_TRUE(c.chooseTarget(f, {20, 0}, goal, target, temporary, hints));
        EXPECT_TRUE(temporary);
        return target;
    };
    // a memory that ends at x = 25, with the local map: its border cells
    // are the local map's free ones (the local planner's part) or grown
    // by the radius from the walls beside them, so the way east is closed
    const TPoint2D small = choose(50);
    EXPECT_GT(small.y, 2.0) << small.x << " " << small.y;
    // one that holds the goal: east, along the corridor
    const TPoint2D sized = choose(exploreMemorySize(50, 0.25, 10, {0, 0}, {45, 0}));
    EXPECT_GT(sized.x, 24.0) << sized.x << " " << sized.y;
    EXPECT_LT(std::abs(sized.y), 0.3);
}
