// From experience to speed without MCL or rawlogs: the afraid level of a grid
// (binning + kernel ridge regression), the speed limit along the route and
// the paper's 10 m comparison, on constructed levels and trajectories.
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/afraid/afraid_level.h>
#include <risknav/afraid/afraid_speed.h>
#include <risknav/afraid/afraid_zones.h>

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"

using namespace risknav::afraid;
using mrpt::math::TPoint2D;

namespace {
// A 20 m x 4 m corridor of 5 cm cells.
mrpt::maps::COccupancyGridMap2D corridor() {
    mrpt::maps::COccupancyGridMap2D g(0, 20, 0, 4, 0.05f);
    g.fill(1.0f);
    return g;
}
}  // namespace

TEST(AfraidLevel, SamplesAreEventsPerPassAndStandingDoesNotDilute) {
    CAfraidGrid g(corridor());
    // Three passes along y = 2.01 through the bin x 5.0..5.25 (5 cells of 5 cm
    // each pass), one event there.
    for (int pass = 0; pass < 3; pass++)
        g.addTraversal(4.0, 2.01, 6.0, 2.01);
    g.addObstacleEvent(5.11, 2.01);
    auto rate = [&] {
        for (const auto& s : afraidSamples(g, 0.25))
            if (std::abs(s.x - 5.125) < 0.01)
                return s.target;
        return -1.0;
    };
    EXPECT_NEAR(rate(), 1.0 / 3, 1e-9);
    // A robot that stands 100 frames in that bin: frames of exposure, no pass.
    for (int i = 0; i < 100; i++)
        g.addExposure(5.11, 2.01);
    EXPECT_NEAR(rate(), 1.0 / 3, 1e-9);
    // Three more passes without an event: the rate halves (it does not fall
    // with more experience of the same rate, only with a lower rate).
    for (int pass = 0; pass < 3; pass++)
        g.addTraversal(6.0, 2.01, 4.0, 2.01);
    EXPECT_NEAR(rate(), 1.0 / 6, 1e-9);
    // An event that falls into the next bin across (no passes there) goes to
    // the bin the path runs through.
    g.addObstacleEvent(5.11, 1.98);
    EXPECT_NEAR(rate(), 2.0 / 6, 1e-9);
}

TEST(AfraidLevel, KernelRegressionOfTheSamplesOnEveryCell) {
    CAfraidGrid g(corridor());
    // A robot line along y = 2 (10 passes), events only around x = 12.
    for (int pass = 0; pass < 10; pass++) {
        g.addTraversal(0.5, 2.0, 19.5, 2.0);
        if (pass < 4)
            g.addObstacleEvent(12.0, 2.0);
    }
    TKrrOptions o;
    const auto level = afraidLevel(g, o, 0.25);
    ASSERT_EQ(level.size(), size_t(g.sizeX()) * g.sizeY());
    // Exactly the regression on the pooled samples, evaluated at the cell centres.
    const auto s = afraidSamples(g, 0.25);
    EXPECT_EQ(level, krrPredictGrid(s, krrFit(s, o), o, g.xMin(), g.yMin(),
                                    g.resolution(), g.sizeX(), g.sizeY()));
    auto at = [&](double x, double y) {
        return level[size_t(g.yToRow(y)) * g.sizeX() + g.xToCol(x)];
    };
    EXPECT_GT(at(12, 2), 0.1f);
    EXPECT_LT(std::abs(at(5, 2)), 1e-3f);
    EXPECT_LT(std::abs(at(12, 3.9)), 0.01f * at(12, 2));  // across the corridor
    // From a saved file, the same level.
    const std::string d = risknav::test::freshDir("afraid-level");
    g.save(d + "/g.afraid");
    EXPECT_EQ(afraidLevel(CAfraidGrid::load(d + "/g.afraid"), o, 0.25), level);
}

TEST(AfraidSpeed, RouteAxisOfAStraightRoute) {
    std::vector<TPoint2D> t;
    for (int i = 0; i <= 200; i++)
        t.emplace_back(20.0 - 0.1 * i, 2.0);  // driven towards -x: axis still +x
    const auto a = routeAxis(t);
    EXPECT_NEAR(a.ux, 1.0, 1e-12);
    EXPECT_NEAR(a.uy, 0.0, 1e-12);
    EXPECT_NEAR(a.mx, 10.0, 1e-9);
    ASSERT_EQ(a.pos.size(), 201u);  // ceil(20 / 0.1) + 1
    EXPECT_NEAR(a.pos.front(), 0.05, 1e-9);
    EXPECT_NEAR(a.pos[100], 10.05, 1e-9);
    EXPECT_EQ(a.binOf(0.0, 2.0), 0);
    EXPECT_EQ(a.binOf(10.07, 3.0), 100);
    EXPECT_EQ(a.binOf(99, 2), 200);  // clamped
    EXPECT_EQ(a.binOf(-9, 2), 0);
}

TEST(AfraidSpeed, CompareSectionOnAConstructedProfile) {
    // 0.05 .. 19.95 m; 0.2 m/s for positions in (8, 10], else 0.8 m/s.
    std::vector<TPoint2D> t{{0, 0}, {10, 0}, {19.95, 0}};
    TRouteAxis a = routeAxis(t);
    a.pos.clear();
    std::vector<double> v;
    for (int i = 0; i < 200; i++) {
        a.pos.push_back(0.05 + 0.1 * i);
        v.push_back(a.pos.back() > 8 && a.pos.back() <= 10 ? 0.2 : 0.8);
    }
    TAfraidZone z;
    z.xMin = 9;
    z.xMax = 10;
    z.yMin = -0.5;
    z.yMax = 0.5;
    const auto c = compareSection(a, v, {z}, 0.2);
    ASSERT_TRUE(c);
    // From 1 m before the zone, 10 m: 2 m at 0.2 m/s and 8 m at 0.8 m/s.
    EXPECT_NEAR(c->fromM, 8.0, 1e-9);
    EXPECT_NEAR(c->toM, 18.0, 1e-9);
    EXPECT_NEAR(c->lengthM, 10.0, 1e-9);
    EXPECT_NEAR(c->timeBeforeS, 50.0, 1e-6);
    EXPECT_NEAR(c->timeAfterS, 2.0 / 0.2 + 8.0 / 0.8, 1e-6);
    EXPECT_NEAR(c->meanSpeedAfter, 10.0 / 20.0, 1e-6);
    // A zone near the end: the section is cut at the route's last position.
    z.xMin = 15;
    z.xMax = 16;
    const auto e = compareSection(a, v, {z}, 0.2);
    ASSERT_TRUE(e);
    EXPECT_NEAR(e->fromM, 14.0, 1e-9);
    EXPECT_NEAR(e->lengthM, 19.95 - 14.0, 1e-9);
    EXPECT_NEAR(e->timeBeforeS, (19.95 - 14.0) / 0.2, 1e-6);
    // (after: the bins whose centres are in the section, each with the step
    // from the previous centre; up to one bin more than the section here)
    EXPECT_NEAR(e->timeAfterS, (19.95 - 14.0) / 0.8, 0.1 / 0.8 + 1e-9);
    // A zone at the start: the section starts at the route's first position.
    z.xMin = 0.3;
    EXPECT_NEAR(compareSection(a, v, {z}, 0.2)->fromM, 0.05, 1e-9);
    // No zone: no comparison.
    EXPECT_FALSE(compareSection(a, v, {}, 0.2));
}

TEST(AfraidSpeed, TenMetreComparisonFromALevelAndATrajectory) {
    // A learned level above the threshold for 8 <= x < 9 on the robot's line,
    // the robot driving from x = 0 to 20 along y = 2.
    CAfraidGrid g(corridor());
    std::vector<float> level(size_t(g.sizeX()) * g.sizeY(), 0.f);
    for (int cy = g.yToRow(1.5); cy <= g.yToRow(2.5); cy++)
        for (int cx = g.xToCol(8.0 + 1e-6); cx < g.xToCol(9.0 + 1e-6); cx++)
            level[size_t(cy) * g.sizeX() + cx] = 0.3f;
    const auto zones = findZones(level, g, 0.04);
    ASSERT_EQ(zones.size(), 1u);
    auto lv = [&](double x, double y) {
        const int cx = g.xToCol(x), cy = g.yToRow(y);
        return g.inside(cx, cy) ? double(level[size_t(cy) * g.sizeX() + cx]) : 0.0;
    };
    std::vector<TPoint2D> t;
    for (int i = 0; i <= 400; i++)
        t.emplace_back(0.05 * i, 2.0);
    TAfraidSpeedParams p;  // 0.8 / 0.2 m/s, 0.9 s, 1 m/s^2: d_stop(0.8) = 1.04 m
    const auto r = routeSpeedProfile(lv, t, zones, p);
    ASSERT_TRUE(r);
    ASSERT_EQ(r->speed.size(), r->axis.pos.size());
    // Slow from d_stop before the zone to its end, fast elsewhere.
    for (size_t i = 0; i < r->speed.size(); i++) {
        const double x = r->axis.pos[i];
        if (x > 8.0 - 1.04 + 0.06 && x < 9.0 - 0.06) {
            EXPECT_EQ(r->speed[i], 0.2) << x;
        } else if (x < 8.0 - 1.04 - 0.06 || x > 9.0 + 0.06) {
            EXPECT_EQ(r->speed[i], 0.8) << x;
        }
    }
    ASSERT_TRUE(r->tenMetre);
    const auto& c = *r->tenMetre;
    EXPECT_NEAR(c.fromM, 7.0, 1e-6);
    EXPECT_NEAR(c.toM, 17.0, 1e-6);
    // Before: 10 m at the learning speed 0.2 m/s. After: the 2 m from 7 to 9 m
    // at 0.2 m/s (within d_stop of the zone, then in it), 8 m at 0.8 m/s;
    // +-1 bin of 10 cm at the zone's edges.
    EXPECT_NEAR(c.timeBeforeS, 50.0, 1e-6);
    EXPECT_NEAR(c.timeAfterS, 2.0 / 0.2 + 8.0 / 0.8, 0.4);
    EXPECT_NEAR(c.meanSpeedAfter, 10.0 / c.timeAfterS, 1e-9);
    // Too short a trajectory: no axis.
    EXPECT_FALSE(routeSpeedProfile(lv, {{0, 2}, {1, 2}}, zones, p));
}
