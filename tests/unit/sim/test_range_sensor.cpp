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
mrpt::maps::COccupancyGridMap2D freeGrid() {
    mrpt::maps::COccupancyGridMap2D g(-10, 10, -10, 10, 0.05f);
    g.fill(1.0f);
    return g;
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
    auto g = freeGrid();
    for (float y = -10; y < 10; y += 0.05f)
        g.setPos(2.0f, y, 0.0f);  // a wall at x = 2
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
