#include <risknav/common/CBadInputError.h>
#include <risknav/risk/CObstacleField.h>
#include <risknav/risk/path_risk.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace risknav::risk;

namespace {
mrpt::maps::COccupancyGridMap2D randomGrid(int w, int h, double res, double fill,
                                           std::mt19937_64& rng) {
    mrpt::maps::COccupancyGridMap2D g(0, float(w * res), 0, float(h * res), float(res));
    g.fill(1.0f);
    std::uniform_real_distribution<double> u(0, 1);
    for (unsigned y = 0; y < g.getSizeY(); y++)
        for (unsigned x = 0; x < g.getSizeX(); x++)
            if (u(rng) < fill)
                g.setCell(x, y, 0.0f);
    return g;
}

Eigen::Matrix2d randomCov(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    const double s1 = 0.01 + u(rng) * 1.0, s2 = 0.01 + u(rng) * 0.5, a = u(rng) * M_PI;
    Eigen::Matrix2d r;
    r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return r * Eigen::Vector2d(s1 * s1, s2 * s2).asDiagonal() * r.transpose();
}
}  // namespace

TEST(DMax, EqualsBruteForceOnRandomGridsAndCovariances) {
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0;
    for (int g = 0; g < 20; g++) {
        const auto grid =
            randomGrid(60 + g * 7, 50 + g * 3, 0.05, 0.002 + 0.01 * u(rng), rng);
        // The outside of the map is an obstacle (the default) on 3 grids of 4:
        // the random grids have no border wall, so the ring often holds D_max.
        risknav::mapping::TObstacleRule rule;
        rule.outside_is_obstacle = g % 4 != 3;
        const CObstacleField f(grid, rule, 0.3 * u(rng));
        for (int k = 0; k < 50; k++, cases++) {
            // Poses anywhere, also off the map and inside obstacles.
            const double x = -0.5 + u(rng) * (grid.getXMax() + 1),
                         y = -0.5 + u(rng) * (grid.getYMax() + 1);
            const Eigen::Matrix2d c = randomCov(rng);
            const TDmax fast = f.dMax(x, y, c), ref = f.dMaxBruteForce(x, y, c);
            ASSERT_NEAR(fast.d, ref.d, 1e-9 * std::max(1.0, ref.d)) << "case " << cases;
            // and the same touch point (up to ties)
            const Eigen::Vector2d tf(fast.touchX - x, fast.touchY - y);
            ASSERT_NEAR(std::sqrt(tf.dot(c.inverse() * tf)), ref.d,
                        1e-6 * std::max(1.0, ref.d));
        }
    }
    EXPECT_EQ(cases, 1000);
}

TEST(DMax, SimpleCasesByHand) {
    mrpt::maps::COccupancyGridMap2D g(0, 10, 0, 10, 0.1f);
    g.fill(1.0f);
    for (int cy = 0; cy < 100; cy++)
        g.setCell(60, cy, 0.0f);  // a wall: the cells x in [6.0, 6.1]
    risknav::mapping::TObstacleRule rule;
    const CObstacleField f(g, rule, 0.0);
    Eigen::Matrix2d c = Eigen::Matrix2d::Identity() * 0.25;  // sigma 0.5 m
    EXPECT_NEAR(f.dMax(5.0, 5.03, c).d, 1.0 / 0.5,
                1e-5);  // the wall face is 1 m away = 2 sigma
    c(0, 0) = 1.0;      // sigma_x 1 m
    EXPECT_NEAR(f.dMax(5.0, 5.03, c).d, 1.0, 1e-5);
    EXPECT_NEAR(f.dMax(5.0, 5.03, c).touchX, 6.0, 1e-5);
    EXPECT_NEAR(f.dMax(5.0, 5.03, c).touchY, 5.03,
                1e-5);  // straight across, not at a cell centre
    // Growing by the robot radius brings the wall closer (cells whose centre is
    // within 0.5 m of a wall cell centre: x in [5.5, 6.6]).
    const CObstacleField f2(g, rule, 0.5);
    EXPECT_NEAR(f2.dMax(5.0, 5.03, c).d, 0.5, 1e-5);
    EXPECT_TRUE(f2.isObstacleAt(5.56, 5.0));
    EXPECT_FALSE(f2.isObstacleAt(5.44, 5.0));
    // Inside an obstacle: 0 (u infinite). A zero covariance: huge but finite.
    EXPECT_EQ(f2.dMax(6.02, 5.05, c).d, 0.0);
    const double dz = f2.dMax(5.05, 5.05, Eigen::Matrix2d::Zero()).d;
    EXPECT_TRUE(std::isfinite(dz));
    EXPECT_GT(dz, 1e5);
    // No obstacle at all (the outside not one either): infinite distance, zero risk.
    mrpt::maps::COccupancyGridMap2D empty(0, 2, 0, 2, 0.1f);
    empty.fill(1.0f);
    rule.outside_is_obstacle = false;
    const CObstacleField fe(empty, rule, 0.5);
    EXPECT_TRUE(std::isinf(fe.dMax(1, 1, c).d));
    EXPECT_EQ(riskDensity(fe.dMax(1, 1, c).d), 0.0);
}

TEST(DMax, UnknownCellsAreConfigurable) {
    mrpt::maps::COccupancyGridMap2D g(0, 5, 0, 5, 0.1f);
    g.fill(1.0f);
    g.setCell(30, 25, 0.5f);  // unknown
    risknav::mapping::TObstacleRule o;
    o.outside_is_obstacle = false;  // only the cell counts
    o.unknown_is_obstacle = true;
    EXPECT_NEAR(CObstacleField(g, o, 0).dMax(2.55, 2.55, Eigen::Matrix2d::Identity()).d,
                0.45, 1e-5);
    o.unknown_is_obstacle = false;
    EXPECT_TRUE(std::isinf(
        CObstacleField(g, o, 0).dMax(2.55, 2.55, Eigen::Matrix2d::Identity()).d));
}

// A map without a border wall: the ring of cells just outside it is an
// obstacle (grown by the robot radius like the rest), so D_max is finite and
// bounded by the map's edge; with outside_is_obstacle = false it is infinite.
TEST(DMax, OpenMapIsBoundedByItsEdge) {
    mrpt::maps::COccupancyGridMap2D g(0, 10, 0, 6, 0.1f);
    g.fill(1.0f);  // no obstacle, no wall
    risknav::mapping::TObstacleRule rule;
    ASSERT_TRUE(rule.outside_is_obstacle);  // the default
    const CObstacleField f(g, rule, 0.3);
    const Eigen::Matrix2d c = Eigen::Matrix2d::Identity() * 0.25;  // sigma 0.5 m
    // The ring at x in [-0.1, 0] grown by 0.3 m covers the cells up to x = 0.3.
    const TDmax d = f.dMax(2.05, 3.05, c);
    ASSERT_TRUE(std::isfinite(d.d));
    EXPECT_NEAR(d.d, (2.05 - 0.3) / 0.5, 1e-6);
    EXPECT_LE(d.d, 2.05 / 0.5);  // never beyond the map's edge
    EXPECT_NEAR(d.touchX, 0.3, 1e-6);
    EXPECT_NEAR(d.touchY, 3.05, 1e-6);
    EXPECT_NEAR(f.dMaxBruteForce(2.05, 3.05, c).d, d.d, 1e-9);
    EXPECT_TRUE(f.isObstacleAt(0.25, 3.0));
    EXPECT_FALSE(f.isObstacleAt(0.35, 3.0));
    // Long in y: the bottom edge holds it.
    Eigen::Matrix2d tall = c;
    tall(1, 1) = 100;
    EXPECT_NEAR(f.dMax(5.05, 2.05, tall).d, (2.05 - 0.3) / 10, 1e-6);
    // Radius 0: the edge itself.
    EXPECT_NEAR(CObstacleField(g, rule, 0).dMax(2.05, 3.05, c).d, 2.05 / 0.5, 1e-6);
    // Off the map: inside the outside obstacle.
    EXPECT_EQ(f.dMax(-1, 3, c).d, 0.0);
    EXPECT_EQ(f.dMaxBruteForce(-1, 3, c).d, 0.0);

    rule.outside_is_obstacle = false;
    const CObstacleField open(g, rule, 0.3);
    EXPECT_TRUE(std::isinf(open.dMax(2.05, 3.05, c).d));
    EXPECT_TRUE(std::isinf(open.dMaxBruteForce(2.05, 3.05, c).d));
    EXPECT_FALSE(open.isObstacleAt(-1, 3));
    EXPECT_EQ(open.obstacleCount(), 0u);
}

TEST(DMax, FieldOptionsAreValidated) {
    mrpt::maps::COccupancyGridMap2D g(0, 2, 0, 2, 0.1f);
    risknav::mapping::TObstacleRule rule;
    EXPECT_THROW(CObstacleField(g, rule, -0.1), risknav::common::CConfigKeyError);
    rule.free_threshold = 0.9;  // above occupied_threshold
    EXPECT_THROW(CObstacleField(g, rule, 0.25), risknav::common::CConfigKeyError);
}

// The error ellipse at Mahalanobis distance D holds 1 - exp(-D^2/2) of the
// probability (Irie et al. section 4.3): 39.3 % at D = 1, 98.9 % at D = 3.
TEST(ErrorEllipse, ProbabilityInsideBySampling) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> n01;
    const Eigen::Matrix2d c = randomCov(rng);
    const Eigen::Matrix2d L = c.llt().matrixL();
    const Eigen::Matrix2d inv = c.inverse();
    const int n = 200000;
    int in1 = 0, in3 = 0;
    for (int i = 0; i < n; i++) {
        const Eigen::Vector2d e = L * Eigen::Vector2d(n01(rng), n01(rng));
        const double d2 = e.dot(inv * e);
        in1 += d2 <= 1.0;
        in3 += d2 <= 9.0;
    }
    EXPECT_NEAR(1 - std::exp(-0.5), 0.393, 5e-4);
    EXPECT_NEAR(1 - std::exp(-4.5), 0.989, 5e-4);
    EXPECT_NEAR(double(in1) / n, 1 - std::exp(-0.5), 0.004);  // 3.6 binomial sigma
    EXPECT_NEAR(double(in3) / n, 1 - std::exp(-4.5), 0.001);
}
