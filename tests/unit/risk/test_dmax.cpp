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

namespace {
// D_max by sampling densely the boundary of the disc-grown obstacles: every
// raw obstacle square grown by r is a rounded square (4 straight edges r away
// from the square, 4 quarter circles of radius r about its corners); the
// outside grown by r is the outside of the map shrunk by r. Sampled points are
// points of the grown set, so the result is >= the true D_max; the true
// minimizer lies on one of these boundaries within `h` [m] of a sample, so
// the result is <= the true D_max + h sqrt(lambda_max(Sigma^-1)).
// Independent of CObstacleField's geometry (it reads only the raw obstacles).
double sampledDmax(const CObstacleField& f, double r, double px, double py,
                   const Eigen::Matrix2d& cov, double h) {
    const auto& df = f.distanceField();
    const double res = df.resolution();
    const Eigen::Matrix2d inv = cov.inverse();
    auto q = [&](double x, double y) {
        const Eigen::Vector2d e(x - px, y - py);
        return e.dot(inv * e);
    };
    // Inside the grown set: 0.
    if (df.rule().outside_is_obstacle && (px - df.xMin() <= r || df.xMax() - px <= r ||
                                          py - df.yMin() <= r || df.yMax() - py <= r))
        return 0;
    struct TSq {
        double lb, xl, yl;
    };
    std::vector<TSq> squares;
    const double sMax = std::sqrt(cov.eigenvalues().real().maxCoeff());
    for (int cy = 0; cy < df.sizeY(); cy++)
        for (int cx = 0; cx < df.sizeX(); cx++)
            if (df.obstacles()[size_t(cy) * df.sizeX() + cx]) {
                const double xl = df.xMin() + cx * res, yl = df.yMin() + cy * res;
                const double dx = std::max({xl - px, 0.0, px - xl - res}),
                             dy = std::max({yl - py, 0.0, py - yl - res});
                const double e = std::hypot(dx, dy);
                if (e <= r)
                    return 0;
                // Euclidean gap / largest sigma: a lower bound of D on it.
                squares.push_back({(e - r) / sMax, xl, yl});
            }
    double best = std::numeric_limits<double>::infinity();
    auto line = [&](double x0, double y0, double x1, double y1) {
        const int n = std::max(1, int(std::ceil(std::hypot(x1 - x0, y1 - y0) / h)));
        for (int k = 0; k <= n; k++)
            best = std::min(best, q(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n));
    };
    if (df.rule().outside_is_obstacle) {
        const double x0 = df.xMin() + r, x1 = df.xMax() - r, y0 = df.yMin() + r,
                     y1 = df.yMax() - r;
        line(x0, y0, x1, y0);
        line(x0, y1, x1, y1);
        line(x0, y0, x0, y1);
        line(x1, y0, x1, y1);
    }
    std::sort(squares.begin(), squares.end(),
              [](const TSq& a, const TSq& b) { return a.lb < b.lb; });
    for (const auto& s : squares) {
        if (s.lb * s.lb >= best)
            break;
        const double xh = s.xl + res, yh = s.yl + res;
        line(s.xl, s.yl - r, xh, s.yl - r);
        line(s.xl, yh + r, xh, yh + r);
        line(s.xl - r, s.yl, s.xl - r, yh);
        line(xh + r, s.yl, xh + r, yh);
        const int n = std::max(4, int(std::ceil(2 * M_PI * r / h)));
        for (double cx : {s.xl, xh})
            for (double cy : {s.yl, yh})
                for (int k = 0; k < n; k++)
                    best = std::min(best, q(cx + r * std::cos(2 * M_PI * k / n),
                                            cy + r * std::sin(2 * M_PI * k / n)));
    }
    return std::sqrt(best);
}
}  // namespace

// The robot radius must not be rounded down to whole cells. D_max
// against a dense sampling of the disc-grown obstacles' boundary, on random
// grids, poses, covariances and radii that are not multiples of the
// resolution: never above it (the safe side, to rounding), and below it by
// at most the sampling's own error. And the point test isObstacleAt() against
// the distance to the nearest square.
TEST(DMax, ExactDiscGrowthAgainstDenseBoundarySampling) {
    std::mt19937_64 rng(88);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0, touching = 0;
    for (int g = 0; g < 12; g++) {
        const auto grid =
            randomGrid(40 + g * 3, 30 + g * 2, 0.05, 0.004 + 0.01 * u(rng), rng);
        risknav::mapping::TObstacleRule rule;
        rule.outside_is_obstacle = g % 3 != 2;
        const double r = 0.013 + 0.33 * u(rng);  // 1.3 to 34 cm: never a whole cell count
        const CObstacleField f(grid, rule, r);
        const auto& df = f.distanceField();
        for (int k = 0; k < 25; k++, cases++) {
            const double x = u(rng) * grid.getXMax(), y = u(rng) * grid.getYMax();
            std::uniform_real_distribution<double> s(0.05, 0.8);
            const double s1 = s(rng), s2 = s(rng), a = u(rng) * M_PI;
            Eigen::Matrix2d rot;
            rot << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
            const Eigen::Matrix2d c =
                rot * Eigen::Vector2d(s1 * s1, s2 * s2).asDiagonal() * rot.transpose();
            const double h = 2e-4;
            const double ref = sampledDmax(f, r, x, y, c, h);
            const double fast = f.dMax(x, y, c).d;
            const double slack = h / std::min(s1, s2);  // h sqrt(lambda_max(Sigma^-1))
            ASSERT_LE(fast, ref + 1e-9 * std::max(1.0, ref)) << "case " << cases;
            ASSERT_GE(fast, ref - slack - 1e-9) << "case " << cases;
            ASSERT_NEAR(fast, f.dMaxBruteForce(x, y, c).d, 1e-9 * std::max(1.0, fast));
            touching += fast == 0;
            // The point test: within r of an obstacle square (or of the outside).
            double e = std::numeric_limits<double>::infinity();
            for (int cy = 0; cy < df.sizeY(); cy++)
                for (int cx = 0; cx < df.sizeX(); cx++)
                    if (df.obstacles()[size_t(cy) * df.sizeX() + cx]) {
                        const double xl = df.xMin() + cx * 0.05,
                                     yl = df.yMin() + cy * 0.05;
                        e = std::min(e,
                                     std::hypot(std::max({xl - x, 0.0, x - xl - 0.05}),
                                                std::max({yl - y, 0.0, y - yl - 0.05})));
                    }
            if (rule.outside_is_obstacle)
                e = std::min(
                    {e, x - df.xMin(), df.xMax() - x, y - df.yMin(), df.yMax() - y});
            if (std::abs(e - r) > 1e-9) {
                ASSERT_EQ(f.isObstacleAt(x, y), e <= r) << "case " << cases << " e " << e;
            }
            ASSERT_EQ(fast == 0, e <= r) << "case " << cases;
        }
    }
    EXPECT_EQ(cases, 300);
    EXPECT_GT(touching, 10);  // the sampling covers robots inside the grown set too
}

// The case: a 1.2 m corridor at 5 cm with r = 0.23 m grows the walls
// by 0.23 m, not by 0.20 m (4 whole cells): D_max is (0.6 - 0.23) / sigma.
TEST(DMax, CorridorWallsGrowByTheExactRadius) {
    mrpt::maps::COccupancyGridMap2D g(0, 6, -1, 2.2, 0.05f);
    g.fill(1.0f);
    for (unsigned cx = 0; cx < g.getSizeX(); cx++)
        for (unsigned cy = 0; cy < g.getSizeY(); cy++)
            if (g.idx2y(cy) < 0 || g.idx2y(cy) > 1.2)
                g.setCell(cx, cy, 0.0f);
    risknav::mapping::TObstacleRule rule;
    rule.outside_is_obstacle = false;
    const CObstacleField f(g, rule, 0.23);
    Eigen::Matrix2d c = Eigen::Matrix2d::Zero();
    c(0, 0) = 1.0;
    c(1, 1) = 0.1 * 0.1;  // lateral sigma 0.1 m
    // (MRPT's grid holds float bounds: the cell edges are off by ~1e-8 m.)
    EXPECT_NEAR(f.dMax(3.0, 0.6, c).d, (0.6 - 0.23) / 0.1, 1e-6);
    EXPECT_NEAR(std::abs(f.dMax(3.0, 0.6, c).touchY - 0.6), 0.6 - 0.23, 1e-6);
    EXPECT_TRUE(f.isObstacleAt(3.0, 0.229));
    EXPECT_FALSE(f.isObstacleAt(3.0, 0.231));
    EXPECT_FALSE(f.isObstacleAt(3.0, 0.969));
    EXPECT_TRUE(f.isObstacleAt(3.0, 0.971));
}
