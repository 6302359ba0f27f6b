#include <risknav/mapping/CDistanceField.h>
#include <risknav/sim/CRangeSensorSim.h>
#include <risknav/sim/range_geometry.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::sim;

TEST(RayDisc, Distances) {
    const TDisc d{3, 0, 0.5, 1};
    EXPECT_NEAR(rayDiscDistance(0, 0, 1, 0, d), 2.5, 1e-12);
    EXPECT_TRUE(std::isinf(rayDiscDistance(0, 0, -1, 0, d)));  // behind
    EXPECT_TRUE(std::isinf(rayDiscDistance(0, 0, 0, 1, d)));   // misses
    EXPECT_EQ(rayDiscDistance(3.1, 0, 1, 0, d), 0.0);          // inside
    // Oblique: ray along y = 0.3 hits the circle at x = 3 - sqrt(0.25 - 0.09) = 2.6.
    EXPECT_NEAR(rayDiscDistance(0, 0.3, 1, 0, d), 2.6, 1e-12);
}

namespace {
mrpt::maps::COccupancyGridMap2D freeCells() {
    mrpt::maps::COccupancyGridMap2D g(-10, 10, -10, 10, 0.05f);
    g.fill(1.0f);
    return g;
}
// A free 20 x 20 m map as the sensors see it (the default rule: the ring
// outside is a wall, 10 m away).
CRayCastMap freeGrid() {
    return CRayCastMap(freeCells(), {});
}
CRangeSensorSim laser(double noise = 0.0) {
    CRangeSensorSim s;
    s.options.beams = 181;
    s.options.fov_deg = 180;
    s.options.max_range = 8;
    s.options.noise_std = noise;
    s.options.x = 0.2;
    return s;
}
}  // namespace

TEST(CRangeSensorSim, SeesAPersonTheMapDoesNotHave) {
    const auto g = freeGrid();
    std::mt19937_64 rng(1);
    const auto scan =
        laser().simulate(g, {0, 0, 0}, {{3, 0, 0.5, 7}}, mrpt::Clock::now(), rng);
    ASSERT_EQ(scan->getScanSize(), 181u);
    EXPECT_TRUE(scan->rightToLeft);
    ASSERT_TRUE(scan->getScanRangeValidity(90));  // the middle beam looks along +x
    EXPECT_NEAR(scan->getScanRange(90), 3 - 0.5 - 0.2,
                1e-5);  // from the sensor, 0.2 m ahead
    // Beams that hit the disc: |angle| <= asin(0.5 / 2.8) = 10.29 deg -> 21 beams of 1
    // deg.
    int valid = 0;
    for (size_t i = 0; i < 181; i++)
        valid += scan->getScanRangeValidity(i);
    EXPECT_EQ(valid, 21);
}

TEST(CRangeSensorSim, WallsOccludePeopleAndTurnWithTheRobot) {
    auto cells = freeCells();
    for (float y = -10; y < 10; y += 0.05f)
        cells.setPos(2.0f, y, 0.0f);  // a wall at x = 2
    const CRayCastMap g(cells, {});
    std::mt19937_64 rng(1);
    const auto scan =
        laser().simulate(g, {0, 0, 0}, {{3, 0, 0.5, 7}}, mrpt::Clock::now(), rng);
    EXPECT_NEAR(scan->getScanRange(90), 2.0 - 0.2,
                0.05);  // the wall, not the person behind it
    // Robot turned to face +y at (0, 0): the person at (0, 3) is straight ahead.
    const auto s2 = laser().simulate(freeGrid(), {0, 0, M_PI / 2}, {{0, 3, 0.5, 7}},
                                     mrpt::Clock::now(), rng);
    EXPECT_NEAR(s2->getScanRange(90), 2.3, 1e-5);
}

TEST(CRangeSensorSim, NoiseHasTheConfiguredSigma) {
    const auto g = freeGrid();
    std::mt19937_64 rng(3);
    const auto s = laser(0.05);
    double sum = 0, sum2 = 0;
    const int n = 800;
    for (int k = 0; k < n; k++) {
        const double r =
            s.simulate(g, {0, 0, 0}, {{3, 0, 0.5, 7}}, mrpt::Clock::now(), rng)
                ->getScanRange(90);
        sum += r;
        sum2 += r * r;
    }
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, 2.3, 4 * 0.05 / std::sqrt(n));
    EXPECT_NEAR(sd / 0.05, 1.0, 0.1);
}

TEST(CRangeSensorSim, PerObjectDropout) {
    const auto g = freeGrid();
    std::mt19937_64 rng(5);
    auto s = laser();
    s.options.dropout_probability = 0.3;
    int seen = 0;
    const int n = 1000;
    for (int k = 0; k < n; k++) {
        const auto scan =
            s.simulate(g, {0, 0, 0}, {{3, 0, 0.5, 7}}, mrpt::Clock::now(), rng);
        int valid = 0;
        for (size_t i = 0; i < 181; i++)
            valid += scan->getScanRangeValidity(i);
        EXPECT_TRUE(valid == 0 || valid == 21);  // the whole object, or nothing of it
        seen += valid > 0;
    }
    // Binomial(1000, 0.7): mean 700, sd 14.5.
    EXPECT_NEAR(seen, 700, 60);
}

TEST(CRangeSensorSim, FullCircleSensor) {
    const auto g = freeGrid();
    std::mt19937_64 rng(1);
    CRangeSensorSim s;
    s.options.fov_deg = 360;
    s.options.beams = 73;  // 5 deg apart, first and last beam both point backwards
    s.options.max_range = 5;
    s.options.noise_std = 0;
    s.options.x = 0;
    const auto scan =
        s.simulate(g, {0, 0, 0}, {{-2, 0, 0.3, 1}}, mrpt::Clock::now(), rng);
    EXPECT_NEAR(scan->getScanRange(0), 1.7, 1e-5);   // -180 deg
    EXPECT_NEAR(scan->getScanRange(72), 1.7, 1e-5);  // +180 deg
    EXPECT_FALSE(scan->getScanRangeValidity(36));    // straight ahead: nothing within 5 m
}

namespace {
// Cells of every kind: free, occupied and the grey values the rule calls
// unknown on both sides of MRPT's 0.5 (MRPT's own ray caster passed through
// P(free) = 0.6 and ended without an echo on 0.5).
mrpt::maps::COccupancyGridMap2D mixedCells() {
    mrpt::maps::COccupancyGridMap2D g(-1, 1, -0.5, 0.5, 0.1f);
    const float values[] = {0.0f, 0.2f,  0.34f, 0.36f, 0.4f, 0.5f,
                            0.6f, 0.64f, 0.66f, 0.8f,  1.0f};
    int k = 0;
    for (unsigned cy = 0; cy < g.getSizeY(); cy++)
        for (unsigned cx = 0; cx < g.getSizeX(); cx++)
            g.setCell(int(cx), int(cy), values[k++ % 11]);
    return g;
}
}  // namespace

// What the rays end on is what the collisions count, cell by cell (the ring
// just off the map included), for each setting of the rule.
TEST(CRayCastMap, EveryCellIsWhatTheCollisionRuleSays) {
    const auto g = mixedCells();
    for (const bool unknown : {true, false})
        for (const bool outside : {true, false})
            for (const double occThr : {0.65, 0.5}) {
                risknav::mapping::TObstacleRule rule;
                rule.unknown_is_obstacle = unknown;
                rule.outside_is_obstacle = outside;
                rule.occupied_threshold = occThr;
                const risknav::mapping::CDistanceField field(g, rule);
                const CRayCastMap rays(g, rule);
                const int ring = outside ? 1 : 0;
                ASSERT_EQ(rays.grid().getSizeX(), g.getSizeX() + 2 * ring);
                ASSERT_EQ(rays.grid().getSizeY(), g.getSizeY() + 2 * ring);
                size_t obstacles = 0;
                for (int cy = -1; cy <= int(g.getSizeY()); cy++)
                    for (int cx = -1; cx <= int(g.getSizeX()); cx++) {
                        const double x = field.idx2x(cx), y = field.idx2y(cy);
                        const bool onMap = field.inside(cx, cy);
                        EXPECT_EQ(rays.isObstacleAt(x, y), field.isObstacle(cx, cy))
                            << "cell " << cx << ", " << cy << " unknown " << unknown
                            << " outside " << outside;
                        if (onMap) {
                            EXPECT_EQ(field.isObstacle(cx, cy),
                                      rule.isObstacle(g.getCell(cx, cy)));
                        }
                        obstacles += onMap && field.isObstacle(cx, cy);
                    }
                EXPECT_EQ(obstacles, field.obstacleCount());
                // the map's cells keep their place in the grid the rays see
                EXPECT_NEAR(rays.grid().getXMin(), g.getXMin() - ring * 0.1, 1e-5);
                EXPECT_NEAR(rays.grid().getYMax(), g.getYMax() + ring * 0.1, 1e-5);
            }
}

// A grey block 3 m ahead, at P(free) 0.4, 0.5 and 0.6 (all unknown to the
// rule): a wall the laser echoes on with unknown_is_obstacle, nothing
// without it (the ring outside is 10 m away, beyond the 8 m range).
TEST(CRangeSensorSim, UnknownCellsEchoExactlyWhenTheRuleMakesThemObstacles) {
    for (const float grey : {0.4f, 0.5f, 0.6f})
        for (const bool unknown : {true, false}) {
            auto cells = freeCells();
            for (float x = 3.0f; x < 4.0f; x += 0.05f)
                for (float y = -1.0f; y < 1.0f; y += 0.05f)
                    cells.setPos(x + 0.025f, y + 0.025f, grey);
            risknav::mapping::TObstacleRule rule;
            rule.unknown_is_obstacle = unknown;
            std::mt19937_64 rng(1);
            const auto scan = laser().simulate(CRayCastMap(cells, rule), {0, 0, 0}, {},
                                               mrpt::Clock::now(), rng);
            SCOPED_TRACE(testing::Message()
                         << "P(free) " << grey << " unknown_is_obstacle " << unknown);
            EXPECT_EQ(scan->getScanRangeValidity(90), unknown);
            if (unknown) {  // the block's edge, from the sensor 0.2 m ahead
                EXPECT_NEAR(scan->getScanRange(90), 3.0 - 0.2, 0.05);
            }
        }
}

// The map's edge without a wall: an echo there when the outside is an
// obstacle (the collisions' ring), none when it is not.
TEST(CRangeSensorSim, TheMapsEdgeEchoesWhenTheOutsideIsAnObstacle) {
    for (const bool outside : {true, false}) {
        risknav::mapping::TObstacleRule rule;
        rule.outside_is_obstacle = outside;
        std::mt19937_64 rng(1);
        const auto scan = laser().simulate(CRayCastMap(freeCells(), rule), {6, 0, 0}, {},
                                           mrpt::Clock::now(), rng);
        EXPECT_EQ(scan->getScanRangeValidity(90), outside);
        if (outside) {
            EXPECT_NEAR(scan->getScanRange(90), 10.0 - 6.2, 0.05);
        }
    }
}
