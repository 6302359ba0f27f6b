#include <risknav/afraid/CAfraidDetector.h>
#include <risknav/afraid/afraid_functions.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/stopping.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::afraid;

TEST(AfraidFunctions, ObsCurAndObsPredictSequences) {
    const double dStop = risknav::common::stoppingDistance(0.2, 0.9, 1.0);  // 0.20 m
    // A wall 1.5 m to the side, a person passing 0.4 m ahead at frames 5-7.
    std::vector<int> cur;
    std::deque<int> hist;
    std::vector<int> pred;
    for (int t = 0; t < 12; t++) {
        std::vector<mrpt::math::TPoint2D> pts = {{0.5, 1.5}, {1.0, 1.5}, {-0.5, -1.5}};
        if (t >= 5 && t <= 7)
            pts.push_back({0.4, 0.05});
        pred.push_back(obsPredict(hist, 3));
        cur.push_back(obsCur(pts, dStop, 0.4, 0.35));
        hist.push_back(cur.back());
    }
    EXPECT_EQ(cur, (std::vector<int>{1, 1, 1, 1, 1, 0, 0, 0, 1, 1, 1, 1}));
    // obs_predict(t) = prod of the previous 3 obs_cur: 0 while the person was seen
    // lately.
    EXPECT_EQ(pred, (std::vector<int>{1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 1}));
    // The flag fires once: new (predict 1) and inside (cur 0), frame 5 only.
    int flags = 0;
    for (size_t t = 0; t < cur.size(); t++)
        flags += afraidFlag(cur[t], pred[t], 10.0, 5.0);
    EXPECT_EQ(flags, 1);
    EXPECT_FALSE(afraidFlag(0, 1, 4.0, 5.0));   // the map explains it: no event
    EXPECT_FALSE(afraidFlag(0, 0, 10.0, 5.0));  // already tracked: expected
    EXPECT_FALSE(afraidFlag(1, 1, 10.0, 5.0));  // nothing inside the collision area
}

TEST(AfraidFunctions, NonBlockedArea) {
    const double dStop = 0.2, beta = 0.4, r = 0.35;
    // Nothing within reach: every one of 181 directions reaches dist_stop.
    EXPECT_NEAR(nonBlockedArea({{3.0, 0}, {0, 1.5}}, dStop, beta, r), 181 * dStop, 1e-9);
    // A point straight ahead within dist_stop + beta blocks the directions
    // whose lateral offset from it is <= r; those reach only that offset.
    const double a = nonBlockedArea({{0.4, 0.0}}, dStop, beta, r);
    // asin(0.2 / 0.4) = 30 deg each side: ~61 directions lose up to 0.2 m each.
    EXPECT_LT(a, 181 * dStop - 3);
    // Closer blocks more.
    EXPECT_LT(nonBlockedArea({{0.3, 0.0}}, dStop, beta, r), a + 1e-9);
}

namespace {
// A 3 m wide corridor along x (walls at y = -1.5 and +1.5), 20 m long.
mrpt::maps::COccupancyGridMap2D corridor() {
    mrpt::maps::COccupancyGridMap2D g(-2, 18, -2.5, 2.5, 0.05f);
    g.fill(1.0f);
    for (unsigned cy = 0; cy < g.getSizeY(); cy++)
        for (unsigned cx = 0; cx < g.getSizeX(); cx++)
            if (std::abs(g.idx2y(cy)) > 1.5)
                g.setCell(cx, cy, 0.0f);
    return g;
}

// A laser scan at pose (0,0,0) in the corridor, plus an optional person disc.
mrpt::obs::CObservation2DRangeScan scanWith(const mrpt::maps::COccupancyGridMap2D& g,
                                            double px, double py) {
    mrpt::obs::CObservation2DRangeScan s;
    s.aperture = float(M_PI);
    s.maxRange = 8;
    s.rightToLeft = true;
    s.sensorPose = mrpt::poses::CPose3D(0.2, 0, 0.3, 0, 0, 0);
    g.laserScanSimulator(s, mrpt::poses::CPose2D(0, 0, 0), 0.5f, 181, 0.0f);
    if (px > -100)
        for (size_t i = 0; i < 181; i++) {
            const double a = -M_PI / 2 + M_PI * i / 180, dx = std::cos(a),
                         dy = std::sin(a);
            const double fx = 0.2 - px, fy = -py, b = fx * dx + fy * dy,
                         c = fx * fx + fy * fy - 0.25 * 0.25;
            const double disc = b * b - c;
            if (disc < 0)
                continue;
            const double t = -b - std::sqrt(disc);
            if (t > 0 && (!s.getScanRangeValidity(i) || t < s.getScanRange(i))) {
                s.setScanRange(i, float(t));
                s.setScanRangeValidity(i, true);
            }
        }
    return s;
}
}  // namespace

TEST(CAfraidDetector, EmptyCorridorMatchesTheMap) {
    const auto g = corridor();
    CAfraidDetector d;
    for (int k = 0; k < 10; k++) {
        const auto st = d.step(scanWith(g, -1000, 0), {0, 0, 0}, 0.2, g);
        EXPECT_NEAR(st.actualArea, st.expectedArea, 1e-9);
        EXPECT_NEAR(st.diff, 0.0, 1e-9);
        EXPECT_FALSE(st.afraid);
        EXPECT_EQ(st.obsCur, 1);
    }
}

TEST(CAfraidDetector, PersonSteppingIntoTheCollisionArea) {
    const auto g = corridor();
    CAfraidDetector d;
    for (int k = 0; k < 6; k++)
        d.step(scanWith(g, -1000, 0), {0, 0, 0}, 0.2, g);  // clear so far
    const auto st =
        d.step(scanWith(g, 0.6, 0.1), {0, 0, 0}, 0.2, g);  // suddenly 0.6 m ahead
    EXPECT_EQ(st.obsCur, 0);
    EXPECT_EQ(st.obsPredict, 1);
    EXPECT_GT(st.diff, d.options.diff_threshold);
    EXPECT_TRUE(st.afraid);
    ASSERT_TRUE(st.obstacleFound);
    EXPECT_NEAR(st.obstacleX, 0.6 - 0.25, 0.05);  // the person's near edge
    // Still there next frame: now expected, no second event.
    EXPECT_FALSE(d.step(scanWith(g, 0.58, 0.1), {0, 0, 0}, 0.2, g).afraid);
}

TEST(CAfraidDetector, PersonWalkingAlongTheCorridorFarAhead) {
    const auto g = corridor();
    CAfraidDetector d;
    for (int k = 0; k < 20; k++) {
        // 3 m ahead, off-centre, walking past: never within the collision area.
        const auto st = d.step(scanWith(g, 3.0 - 0.1 * k, 0.8), {0, 0, 0}, 0.2, g);
        EXPECT_EQ(st.obsCur, 1) << k;
        EXPECT_FALSE(st.afraid) << k;
    }
}

// The detector's robot is the [Robot] schema: its swept half-width is radius
// + lateral_margin (0.25 + 0.1 = 0.35 m by default, the former half_width);
// options set from code run the same validate(); save/load round-trips.
TEST(CAfraidDetector, RobotSchemaOptionsValidateAndRoundTrip) {
    using risknav::common::CConfigKeyError;
    CAfraidDetector d;
    EXPECT_EQ(d.halfWidth(), 0.35);
    EXPECT_NO_THROW(d.validate());
    d.robot.radius = 0.3;
    d.robot.t_delay = 0.5;
    d.options.lateral_margin = 0.05;
    d.options.directions = 91;
    EXPECT_NEAR(d.halfWidth(), 0.35, 1e-15);
    mrpt::config::CConfigFileMemory m;
    d.saveToConfigFile(m);
    CAfraidDetector r;
    r.loadFromConfigFile(m);
    mrpt::config::CConfigFileMemory m2;
    r.saveToConfigFile(m2);
    EXPECT_EQ(m.getContent(), m2.getContent());
    EXPECT_EQ(r.robot.radius, 0.3);
    EXPECT_EQ(r.robot.t_delay, 0.5);
    EXPECT_EQ(r.options.lateral_margin, 0.05);
    EXPECT_EQ(r.options.directions, 91);
    r.options.lateral_margin = -0.1;
    EXPECT_THROW(r.validate(), CConfigKeyError);
    r.options.lateral_margin = 0.1;
    r.robot.decel = 0;
    EXPECT_THROW(r.validate(), CConfigKeyError);
}
