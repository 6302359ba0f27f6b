// The global planner: grid A* against Bellman-Ford, the widest way, and
// CGlobalPlanner's plans, replans and reasons on synthetic maps.
#include <risknav/common/config_read.h>
#include <risknav/planning/CGlobalPlanner.h>
#include <risknav/planning/grid_search.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <limits>
#include <random>

using namespace risknav;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();

// Bellman-Ford over the same graph as gridAStar (8-connected, a move costs
// its length times the mean of the two cells' costs, no corner cutting):
// relax every edge until nothing changes. Independent of the A* code.
double bellmanFord(const planning::TCostGrid& g, int s, int t) {
    const size_t n = g.cost.size();
    std::vector<double> d(n, std::numeric_limits<double>::infinity());
    if (!(g.cost[size_t(s)] < kInf) || !(g.cost[size_t(t)] < kInf))
        return d[0];
    d[size_t(s)] = 0;
    for (bool changed = true; changed;) {
        changed = false;
        for (int y = 0; y < g.h; y++)
            for (int x = 0; x < g.w; x++) {
                const size_t a = g.index(x, y);
                if (!(g.cost[a] < kInf) || !(d[a] < 1e300))
                    continue;
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++) {
                        if (!dx && !dy)
                            continue;
                        const int nx = x + dx, ny = y + dy;
                        if (!g.inside(nx, ny))
                            continue;
                        const size_t b = g.index(nx, ny);
                        if (!(g.cost[b] < kInf))
                            continue;
                        if (dx && dy &&
                            (!(g.cost[g.index(nx, y)] < kInf) ||
                             !(g.cost[g.index(x, ny)] < kInf)))
                            continue;
                        const double len =
                            (dx && dy ? std::sqrt(2.0) : 1.0) * g.resolution;
                        const double nd = d[a] + len * 0.5 * (g.cost[a] + g.cost[b]);
                        if (nd < d[b] - 1e-9) {
                            d[b] = nd;
                            changed = true;
                        }
                    }
            }
    }
    return d[size_t(t)];
}

// A map of w x h metres at 5 cm, free, with a border wall; `wall` marks
// rectangles [x0, x1] x [y0, y1] as occupied.
struct TRect {
    double x0, y0, x1, y1;
};
mrpt::maps::COccupancyGridMap2D makeMap(double w, double h,
                                        const std::vector<TRect>& walls) {
    mrpt::maps::COccupancyGridMap2D g(0, float(w), 0, float(h), 0.05f);
    g.fill(1.0f);
    for (unsigned cy = 0; cy < g.getSizeY(); cy++)
        for (unsigned cx = 0; cx < g.getSizeX(); cx++) {
            const double x = g.idx2x(cx), y = g.idx2y(cy);
            bool occ =
                cx == 0 || cy == 0 || cx + 1 == g.getSizeX() || cy + 1 == g.getSizeY();
            for (const auto& r : walls)
                occ = occ || (x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1);
            if (occ)
                g.setCell(int(cx), int(cy), 0.0f);
        }
    return g;
}

planning::CGlobalPlanner plannerOn(const mrpt::maps::COccupancyGridMap2D& g,
                                   double disc = 0.35, const char* map = "known") {
    planning::CGlobalPlanner p;
    p.options.margin = 0;  // the disc as given
    p.options.map = map;
    mapping::TObstacleRule rule;
    p.setMap(g, rule, disc);
    return p;
}
}  // namespace

TEST(GridSearch, AStarCostEqualsBellmanFordOnRandomGrids) {
    std::mt19937 rng(7);
    int found = 0, none = 0;
    for (int trial = 0; trial < 60; trial++) {
        planning::TCostGrid g;
        g.w = 6 + int(rng() % 10);
        g.h = 5 + int(rng() % 10);
        g.resolution = 0.1;
        std::uniform_real_distribution<float> cost(1.0f, 6.0f);
        g.cost.resize(size_t(g.w * g.h));
        for (auto& c : g.cost)
            c = (rng() % 100) < 28 ? kInf : cost(rng);
        const int s = int(rng() % g.cost.size()), t = int(rng() % g.cost.size());
        const auto p = planning::gridAStar(g, s, t);
        const double bf = bellmanFord(g, s, t);
        if (std::isinf(bf)) {
            EXPECT_TRUE(p.cells.empty()) << trial;
            none++;
            continue;
        }
        found++;
        ASSERT_FALSE(p.cells.empty()) << trial;
        EXPECT_NEAR(p.cost, bf, 1e-4 * bf) << trial;
        // the cells are a chain of neighbours from s to t, costing p.cost
        EXPECT_EQ(p.cells.front(), s);
        EXPECT_EQ(p.cells.back(), t);
        double sum = 0;
        for (size_t k = 1; k < p.cells.size(); k++) {
            const int a = p.cells[k - 1], b = p.cells[k];
            const int dx = std::abs(a % g.w - b % g.w), dy = std::abs(a / g.w - b / g.w);
            ASSERT_TRUE(dx <= 1 && dy <= 1 && dx + dy > 0);
            sum += (dx && dy ? std::sqrt(2.0) : 1.0) * g.resolution * 0.5 *
                   (g.cost[size_t(a)] + g.cost[size_t(b)]);
        }
        EXPECT_NEAR(sum, p.cost, 1e-4 * sum);
    }
    // both kinds of case were tried
    EXPECT_GT(found, 20);
    EXPECT_GT(none, 3);
}

TEST(GridSearch, WidestWayIsTheNarrowestClearanceOfTheBestWay) {
    // a 7 x 3 strip: the middle column's clearance 0.2 is the bottleneck of
    // the top row (0.9 elsewhere); the bottom row is 0.5 throughout
    const int w = 7, h = 3;
    std::vector<float> c(w * h, 0.0f);
    for (int x = 0; x < w; x++) {
        c[size_t(2 * w + x)] = x == 3 ? 0.2f : 0.9f;
        c[size_t(0 * w + x)] = 0.5f;
        c[size_t(1 * w + x)] = x == 0 || x == w - 1 ? 0.9f : 0.0f;
    }
    EXPECT_FLOAT_EQ(float(planning::widestWayClearance(c, w, h, 2 * w, 2 * w + w - 1)),
                    0.5f);
    c[size_t(0 * w + 3)] = 0.0f;  // the bottom row cut: only the top row's 0.2
    EXPECT_FLOAT_EQ(float(planning::widestWayClearance(c, w, h, 2 * w, 2 * w + w - 1)),
                    0.2f);
    c[size_t(2 * w + 3)] = 0.0f;  // both cut
    EXPECT_EQ(planning::widestWayClearance(c, w, h, 2 * w, 2 * w + w - 1), 0.0);
}

TEST(CGlobalPlanner, AGoalBehindAWallIsPlannedAroundIt) {
    // 10 x 6 m, a wall at x = 5 from the bottom to y = 4.8: the way round
    // its top end
    const auto g = makeMap(10, 6, {{4.9, 0, 5.1, 4.8}});
    const auto p = plannerOn(g);
    const auto plan = p.plan({2, 1}, {8, 1});
    ASSERT_TRUE(plan.found) << plan.reason;
    // round the wall's end (5, 4.8) with the disc: at least the two straight
    // legs to a point 0.35 m above it, at most the sides of a box round it
    EXPECT_GT(plan.length, 2 * std::hypot(3.0, 4.8 + 0.35 - 1.0));
    EXPECT_LT(plan.length, 2 * (4.8 + 0.6 - 1.0) + 6);
    double topY = 0;
    for (const auto& q : plan.points) {
        topY = std::max(topY, q.y);
        // every point holds the disc
        EXPECT_GE(p.field().clearanceAt(q.x, q.y) + 1e-6, 0.35) << q.x << " " << q.y;
    }
    EXPECT_GT(topY, 4.8 + 0.35);
    EXPECT_NEAR(plan.points.front().x, 2, 1e-9);
    EXPECT_NEAR(plan.points.back().x, 8, 1e-9);
    // the clearance cost keeps the plan off the wall's end: the gap above it
    // is 1.2 m (4.8 to 5.95), the plan passes near its middle
    EXPECT_GT(plan.minClearance, 0.45);
}

TEST(CGlobalPlanner, NoPathSaysWhy) {
    // a wall across the map with a 0.5 m gap: too narrow for a 0.35 m disc
    const auto g = makeMap(10, 6, {{4.9, 0, 5.1, 2.75}, {4.9, 3.25, 5.1, 6}});
    const auto p = plannerOn(g);
    auto plan = p.plan({2, 3}, {8, 3});
    EXPECT_FALSE(plan.found);
    EXPECT_EQ(plan.failure, "narrow_gap") << plan.reason;
    EXPECT_NE(plan.reason.find("gap of about 0.4"), std::string::npos) << plan.reason;
    // a smaller disc fits
    EXPECT_TRUE(plannerOn(g, 0.2).plan({2, 3}, {8, 3}).found);
    // closed: disconnected
    const auto closed = makeMap(10, 6, {{4.9, 0, 5.1, 6}});
    plan = plannerOn(closed).plan({2, 3}, {8, 3});
    EXPECT_EQ(plan.failure, "disconnected") << plan.reason;
    // start and goal on an obstacle, or off the map
    EXPECT_EQ(plannerOn(closed).plan({5, 3}, {8, 3}).failure, "start_blocked");
    EXPECT_EQ(plannerOn(closed).plan({2, 3}, {5, 3}).failure, "goal_blocked");
    EXPECT_EQ(plannerOn(closed).plan({2, 3}, {18, 3}).failure, "goal_blocked");
}

TEST(CGlobalPlanner, AStartNearAWallLeavesIt) {
    // the robot 0.2 m from the wall (less than the disc): it may leave
    const auto g = makeMap(10, 6, {});
    const auto p = plannerOn(g);
    const auto plan = p.plan({2, 0.05 + 0.2 + 0.025}, {8, 3});
    EXPECT_TRUE(plan.found) << plan.reason;
}

TEST(CGlobalPlanner, ABlockedCorridorIsReplannedThroughTheOther) {
    // two corridors from the left room to the right one: the lower (y 1-2.4)
    // is the shorter way, the upper (y 4.4-5.8) the longer
    const auto g = makeMap(14, 6.2, {{3, 0, 11, 1}, {3, 2.4, 11, 4.4}});
    auto p = plannerOn(g);
    const TPoint2D goal(12.5, 1.7);
    auto ev = p.update(TPose2D(1.5, 1.7, 0), goal, 0.0);
    ASSERT_TRUE(ev);
    EXPECT_EQ(ev->why, "new_target");
    ASSERT_TRUE(p.current().found);
    double maxY = 0;
    for (const auto& q : p.current().points)
        maxY = std::max(maxY, q.y);
    EXPECT_LT(maxY, 2.4);  // the lower corridor
    // nothing sensed: no replan
    EXPECT_FALSE(p.update(TPose2D(1.6, 1.7, 0), goal, 0.2));
    // a box across the lower corridor at x = 5, seen from (2, 1.7): points
    // on its face, robot frame (x ahead)
    std::vector<TPoint2D> pts;
    for (double y = 1.0; y <= 2.4; y += 0.05)
        pts.emplace_back(5.0 - 2.0, y - 1.7);
    p.addSensed(TPose2D(2, 1.7, 0), pts, 1.0);
    ev = p.update(TPose2D(2, 1.7, 0), goal, 1.2);
    ASSERT_TRUE(ev);
    EXPECT_EQ(ev->why, "blocked");
    ASSERT_TRUE(p.current().found);
    maxY = 0;
    for (const auto& q : p.current().points)
        maxY = std::max(maxY, q.y);
    EXPECT_GT(maxY, 4.4);  // the upper corridor now
    // once a later scan sees through where the box was (it moved away: the
    // beams end on the far room's wall and on the corridor's walls), the
    // memory forgets it, and the map's way is free again
    std::vector<TPoint2D> through;
    for (double y = 1.05; y <= 2.36; y += 0.025)
        through.emplace_back(13.95 - 2.0, y - 1.7);
    for (double x = 5.0; x <= 11; x += 0.025) {
        through.emplace_back(x - 2.0, 1.0 - 1.7);
        through.emplace_back(x - 2.0, 2.4 - 1.7);
    }
    p.addSensed(TPose2D(2, 1.7, 0), through, 3.5);
    auto fresh = p.plan({2, 1.7}, goal, true);
    ASSERT_TRUE(fresh.found);
    maxY = 0;
    for (const auto& q : fresh.points)
        maxY = std::max(maxY, q.y);
    EXPECT_LT(maxY, 2.4);
}

TEST(CGlobalPlanner, StrayingAndAPoseJumpReplan) {
    const auto g = makeMap(12, 8, {});
    auto p = plannerOn(g);
    const TPoint2D goal(10, 4);
    ASSERT_TRUE(p.update(TPose2D(2, 4, 0), goal, 0));
    EXPECT_FALSE(p.update(TPose2D(2.2, 4.1, 0), goal, 0.2));
    // 0.6 m in one cycle: a localization correction
    auto ev = p.update(TPose2D(2.2, 4.7, 0), goal, 0.4);
    ASSERT_TRUE(ev);
    EXPECT_EQ(ev->why, "pose_jump");
    // pushed 1.5 m off the plan over several cycles
    double y = 4.7;
    std::optional<planning::TReplanEvent> last;
    for (int k = 0; k < 10 && !last; k++) {
        y += 0.2;
        last = p.update(TPose2D(2.4, y, 0), goal, 0.6 + 0.2 * k);
    }
    ASSERT_TRUE(last);
    EXPECT_EQ(last->why, "strayed");
    // the guide point lies ahead on the plan, about lookahead away
    const auto gp = p.guidePoint(TPose2D(2.4, y, 0));
    ASSERT_TRUE(gp);
    EXPECT_NEAR(std::hypot(gp->x - 2.4, gp->y - y), p.options.lookahead, 0.1);
    EXPECT_GT(gp->x, 2.4);
}

TEST(CGlobalPlanner, OptionsAreChecked) {
    planning::CGlobalPlanner::TOptions o;
    o.lookahead = 0;
    EXPECT_THROW(o.validate(), std::exception);
    o = {};
    o.clearance_weight = -1;
    EXPECT_THROW(o.validate(), std::exception);
    o = {};
    EXPECT_NO_THROW(o.validate());
}

namespace {
// Winding number of the closed polygon `loop` about point p (the sum of the
// signed angles its edges subtend): independent of the raster test the
// planner uses.
int windingNumber(const std::vector<TPoint2D>& loop, const TPoint2D& p) {
    double sum = 0;
    for (size_t i = 0; i < loop.size(); i++) {
        const auto& a = loop[i];
        const auto& b = loop[(i + 1) % loop.size()];
        sum += std::atan2((a.x - p.x) * (b.y - p.y) - (a.y - p.y) * (b.x - p.x),
                          (a.x - p.x) * (b.x - p.x) + (a.y - p.y) * (b.y - p.y));
    }
    return int(std::lround(sum / (2 * M_PI)));
}
}  // namespace

TEST(CGlobalPlanner, AlternativesAreOfDistinctHomotopyClasses) {
    // the two-corridor map: the block between them (x 3-11, y 2.4-4.4)
    // separates the classes; the candidates' loop must wind round it
    const auto g = makeMap(14, 6.2, {{3, 0, 11, 1}, {3, 2.4, 11, 4.4}});
    const auto p = plannerOn(g);
    const auto alts = p.alternatives({1.5, 1.7}, {12.5, 1.7}, 3);
    ASSERT_EQ(alts.size(), 2u);  // only two classes exist (the lower block is a wall)
    EXPECT_TRUE(alts[0].found && alts[1].found);
    EXPECT_LT(alts[0].cost, alts[1].cost + 1e-9);  // the least-cost way first
    std::vector<TPoint2D> loop = alts[0].points;
    loop.insert(loop.end(), alts[1].points.rbegin(), alts[1].points.rend());
    EXPECT_EQ(std::abs(windingNumber(loop, {7, 3.4})), 1);
    // a map with one way only: one candidate
    const auto one = makeMap(14, 6.2, {{3, 0, 11, 1}, {3, 2.4, 11, 6.2}});
    EXPECT_EQ(plannerOn(one).alternatives({1.5, 1.7}, {12.5, 1.7}, 3).size(), 1u);
    // an open room: the straight way; a detour round nothing is the same class
    const auto open = makeMap(14, 6.2, {});
    EXPECT_EQ(plannerOn(open).alternatives({1.5, 1.7}, {12.5, 1.7}, 3).size(), 1u);
}

TEST(CGlobalPlanner, ANewRunForgetsTheLastRunsSensedObstacles) {
    // a run's clock starts again: the last run's sensed cells must not
    // close a way in the next one
    const auto g = makeMap(14, 6.2, {{3, 0, 11, 1}, {3, 2.4, 11, 4.4}});
    auto p = plannerOn(g);
    std::vector<TPoint2D> pts;
    for (double y = 1.0; y <= 2.4; y += 0.05)
        pts.emplace_back(3.0, y - 1.7);
    p.addSensed(TPose2D(2, 1.7, 0), pts, 100.0);
    ASSERT_GT(p.plan({2, 1.7}, {12.5, 1.7}, true).length, 14.0);  // the upper corridor
    p.resetFollowing();
    p.update(TPose2D(2, 1.7, 0), {12.5, 1.7}, 0.0);  // the next run's clock
    ASSERT_TRUE(p.current().found);
    EXPECT_LT(p.current().length, 11.0);  // the lower corridor again
}

TEST(CGlobalPlanner, ABuiltMapKeepsWhatItSensedUntilABeamPassesThrough) {
    // map = built: the planner is given the extent only (every cell free);
    // a wall the laser senses across the straight way closes it for good
    // (not only obstacle_memory seconds), until a later beam passes through
    const auto blank = makeMap(12, 8, {});
    planning::CGlobalPlanner p;
    p.options.margin = 0;
    p.options.map = "built";
    p.options.obstacle_memory = 5;
    p.setMap(blank, mapping::TObstacleRule{}, 0.35);
    const TPoint2D goal(10, 4);
    EXPECT_LT(p.plan({2, 4}, goal, true).length, 8.0 + 0.1);  // straight
    // a 4 m wall at x = 6 (y 2-6), seen from (2, 4): robot frame points
    std::vector<TPoint2D> wall;
    for (double y = 2.0; y <= 6.0; y += 0.05)
        wall.emplace_back(6.0 - 2.0, y - 4.0);
    p.addSensed(TPose2D(2, 4, 0), wall, 1.0);
    // an hour later, nothing else sensed: still round the wall
    p.addSensed(TPose2D(2, 4, 0), {}, 3600.0);
    const auto round = p.plan({2, 4}, goal, true);
    ASSERT_TRUE(round.found) << round.reason;
    EXPECT_GT(round.length, 8.0 + 0.5);
    double far = 0;
    for (const auto& q : round.points)
        far = std::max(far, std::abs(q.y - 4.0));
    EXPECT_GT(far, 2.0 + 0.35 - 0.05);  // past the wall's end with the disc
    // the wall moved away: beams from (2, 4) end on the far border
    std::vector<TPoint2D> through;
    for (double y = 2.0; y <= 6.0; y += 0.025)
        through.emplace_back(11.95 - 2.0, y - 4.0);
    p.addSensed(TPose2D(2, 4, 0), through, 3601.0);
    EXPECT_LT(p.plan({2, 4}, goal, true).length, 8.0 + 0.1);
    // with map = known the same wall is forgotten after obstacle_memory
    planning::CGlobalPlanner k;
    k.options.margin = 0;
    k.options.obstacle_memory = 5;
    k.setMap(blank, mapping::TObstacleRule{}, 0.35);
    k.addSensed(TPose2D(2, 4, 0), wall, 1.0);
    EXPECT_GT(k.plan({2, 4}, goal, true).length, 8.0 + 0.5);
    k.addSensed(TPose2D(2, 4, 0), {}, 10.0);
    EXPECT_LT(k.plan({2, 4}, goal, true).length, 8.0 + 0.1);
}

TEST(CGlobalPlanner, AGapTheDiscFitsWithinACellOfTheSensedPointsIsPlannedOnce) {
    // map = built, a sensed wall across the room at x = 6 with one gap
    // whose points stand 0.76 m apart: the 0.35 m disc keeps off them by
    // its whole radius nowhere (the cells' centres, 0.325 m), within one
    // cell it does. The way goes through the gap and is not found blocked
    // by the same points a cycle later (no replan every second).
    const auto blank = makeMap(12, 8, {});
    planning::CGlobalPlanner p;
    p.options.margin = 0;
    p.options.map = "built";
    p.setMap(blank, mapping::TObstacleRule{}, 0.35);
    std::vector<TPoint2D> wall;
    for (int k = 5; k <= 395; k++)  // y = 0.1 .. 7.9 m every 2 cm
        if (k <= 181 || k >= 219)   // the gap's points at 3.62 and 4.38 m
            wall.emplace_back(6.0 - 2.0, 0.02 * k - 4.0);
    p.addSensed(TPose2D(2, 4, 0), wall, 0.0);
    EXPECT_FALSE(p.plan({2, 4}, {10, 4}, true).found);  // the whole disc
    const auto ev = p.update(TPose2D(2, 4, 0), {10, 4}, 0.0);
    ASSERT_TRUE(ev);
    ASSERT_TRUE(p.current().found) << p.current().reason;
    EXPECT_LT(p.current().length, 8.0 + 0.2);  // straight through the gap
    p.addSensed(TPose2D(2, 4, 0), wall, 2.0);
    EXPECT_FALSE(p.update(TPose2D(2, 4, 0), {10, 4}, 2.0));
}

TEST(CGlobalPlanner, ABuiltMapTakesAGapWithinACellOverALongDetour) {
    // map = built, a sensed wall at x = 6 with a gap whose points stand
    // 0.76 m apart (the 0.35 m disc fits it only within a cell of them, as
    // above). Round the wall's end is a way for the whole disc: taken when
    // it is about as short, not when it is a long detour (the laser's
    // points sit up to a cell in front of a surface: the gap is there).
    auto wallWithGap = [](double y0, double y1) {
        std::vector<TPoint2D> w;
        for (double y = y0; y <= y1 + 1e-9; y += 0.02)
            if (y < 3.63 || y > 4.37)  // the gap's points at 3.62 and 4.38 m
                w.emplace_back(6.0 - 2.0, y - 4.0);
        return w;
    };
    const auto blank = makeMap(12, 20, {});
    for (const bool longDetour : {true, false}) {
        planning::CGlobalPlanner p;
        p.options.margin = 0;
        p.options.map = "built";
        p.setMap(blank, mapping::TObstacleRule{}, 0.35);
        // long: the wall from the floor to y = 14 (round its end ~23 m);
        // short: y 2.5-5.5 (round its end ~9 m, the straight way 8 m)
        p.addSensed(TPose2D(2, 4, 0),
                    longDetour ? wallWithGap(0.1, 14) : wallWithGap(2.5, 5.5), 0.0);
        ASSERT_TRUE(p.update(TPose2D(2, 4, 0), {10, 4}, 0.0));
        ASSERT_TRUE(p.current().found) << p.current().reason;
        if (longDetour)
            EXPECT_LT(p.current().length, 8.0 + 0.2);  // through the gap
        else
            EXPECT_GT(p.current().length, 8.5);  // round the end, the whole disc off
        // and not found blocked by the same points a cycle later
        p.addSensed(TPose2D(2, 4, 0),
                    longDetour ? wallWithGap(0.1, 14) : wallWithGap(2.5, 5.5), 2.0);
        EXPECT_FALSE(p.update(TPose2D(2, 4, 0), {10, 4}, 2.0));
    }
}

TEST(CGlobalPlanner, ABeamDoesNotForgetACellSensedAMomentAgo) {
    // Two scans' beams that graze a post's corner cell mark it and clear it
    // in turn: two ways through one gap were each blocked in turn, and the
    // robot turned between them for minutes. A beam clears a cell only
    // 2 s after it was last sensed.
    const auto blank = makeMap(12, 8, {});
    auto p = plannerOn(blank, 0.33, "built");
    const TPose2D pose(2, 4, 0);
    const double t0 = 1.7e9;  // clock time, as a robot's
    p.addSensed(pose, {{0.4, 1.6}}, t0);
    auto seen = [&] {
        for (const auto& q : p.sensedNear(pose, 2.0))
            if (std::hypot(q.x - 0.4, q.y - 1.6) < 0.08)
                return true;
        return false;
    };
    p.addSensed(pose, {{0.6, 2.4}}, t0 + 1.0);  // its beam passes the post's cell
    EXPECT_TRUE(seen());
    p.addSensed(pose, {{0.4, 1.6}}, t0 + 1.2);  // seen again
    p.addSensed(pose, {{0.6, 2.4}}, t0 + 3.0);
    EXPECT_TRUE(seen());
    p.addSensed(pose, {{0.6, 2.4}}, t0 + 3.3);  // 2.1 s after it was last seen
    EXPECT_FALSE(seen());
}

TEST(CGlobalPlanner, ASensedObstacleIsRememberedOnAClockOfTodaysTime) {
    // obstacle_memory counts seconds of a clock that reads ~1.7e9 s: kept
    // as a float that resolves only 128 s, a cell sensed 1 s ago could
    // count as 40 s old, or one 90 s old as new
    const auto blank = makeMap(12, 8, {});
    auto p = plannerOn(blank, 0.33);
    p.options.obstacle_memory = 30;
    const TPose2D pose(2, 4, 0);
    for (const double t0 : {1.6e9 + 40, 1.7e9 + 100, 1.7e9 + 127}) {
        p.resetFollowing();
        p.addSensed(pose, {{1.5, 0.0}}, t0);
        EXPECT_EQ(p.sensedNear(pose, 2.0).size(), 1u) << t0;
        p.addSensed(pose, {}, t0 + 29);
        EXPECT_EQ(p.sensedNear(pose, 2.0).size(), 1u) << t0;
        p.addSensed(pose, {}, t0 + 31);
        EXPECT_EQ(p.sensedNear(pose, 2.0).size(), 0u) << t0;
    }
}

TEST(CGlobalPlanner, ABeamFromTheCentreDoesNotForgetAPostBesideTheRobot) {
    // The planner draws each beam from the robot's centre, but a laser
    // sits off it (e.g. 0.2 m ahead): beside the robot the centre's line
    // passes through a post the laser's beam did not. Near the robot (the
    // disc + 0.2 m) nothing is forgotten; further out beams still clear.
    const auto blank = makeMap(12, 8, {});
    auto p = plannerOn(blank, 0.33, "built");
    const TPose2D pose(2, 4, 0);
    // a post 0.41 m from the centre, ahead-left, and one 1.65 m out
    p.addSensed(pose, {{0.1, 0.4}, {0.4, 1.6}}, 0.0);
    auto near = [&](double x, double y) {
        for (const auto& q : p.sensedNear(pose, 2.0))
            if (std::hypot(q.x - x, q.y - y) < 0.08)
                return true;
        return false;
    };
    ASSERT_TRUE(near(0.1, 0.4));
    ASSERT_TRUE(near(0.4, 1.6));
    // a wall point further along the same line from the centre: its line
    // passes through both posts' cells
    p.addSensed(pose, {{0.6, 2.4}}, 3.0);
    EXPECT_TRUE(near(0.1, 0.4));   // kept: beside the robot
    EXPECT_FALSE(near(0.4, 1.6));  // seen through: gone
}

TEST(CGlobalPlanner, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    // config/risknav-navigate.ini documents [GlobalPlanner] key by key, with
    // the defaults (some written as 2.0 for 2: compared as numbers)
    mrpt::config::CConfigFileMemory doc(risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-navigate.ini")));
    const auto keys = planning::CGlobalPlanner::TOptions().keys();
    ASSERT_EQ(keys.size(), 11u);
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists("GlobalPlanner", k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        std::string v = doc.read_string("GlobalPlanner", k.key, "");
        v = common::trim(v.substr(0, v.find("//")));
        double documented = 0, declared = 0;
        if (common::parseNumber(v, documented) &&
            common::parseNumber(k.defaultText, declared))
            EXPECT_EQ(documented, declared) << k.key;
        else
            EXPECT_EQ(v, k.defaultText) << k.key;
    }
}
