#include <risknav/afraid/CAfraidDetector.h>
#include <risknav/afraid/afraid_functions.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/scan_points.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::afraid;

TEST(AfraidFunctions, ObsCurAndObsPredictSequences) {
    const double dStop = risknav::common::stoppingDistance(0.2, 0.9, 1.0);  // 0.20 m
    const TCollisionArea area{0.25 + dStop + 0.4, 0.35};                    // 0.85 m
    // A wall 1.5 m to the side, a person passing 0.4 m ahead at frames 5-7.
    std::vector<int> cur;
    std::deque<int> hist;
    std::vector<int> pred;
    for (int t = 0; t < 12; t++) {
        std::vector<mrpt::math::TPoint2D> pts = {{0.5, 1.5}, {1.0, 1.5}, {-0.5, -1.5}};
        if (t >= 5 && t <= 7)
            pts.push_back({0.4, 0.05});
        pred.push_back(obsPredict(hist, 3));
        cur.push_back(obsCur(pts, area));
        hist.push_back(cur.back());
    }
    EXPECT_EQ(cur, (std::vector<int>{1, 1, 1, 1, 1, 0, 0, 0, 1, 1, 1, 1}));
    // obs_predict(t) = prod of the previous 3 entries: 0 while the person was
    // seen lately.
    EXPECT_EQ(pred, (std::vector<int>{1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 1}));
    int flags = 0;
    for (size_t t = 0; t < cur.size(); t++)
        flags += afraidFlag(cur[t], pred[t], 0.2, 0.05);
    EXPECT_EQ(flags, 1);
    EXPECT_FALSE(afraidFlag(0, 1, 0.04, 0.05));  // the map explains it: no event
    EXPECT_FALSE(afraidFlag(0, 0, 0.2, 0.05));   // already tracked: expected
    EXPECT_FALSE(afraidFlag(1, 1, 0.2, 0.05));   // nothing inside the collision area
}

TEST(AfraidFunctions, OneCollisionAreaForEqs5And8) {
    const TCollisionArea area{0.85, 0.35};
    EXPECT_TRUE(area.contains({0.8, 0.3}));
    EXPECT_FALSE(area.contains({0.9, 0.0}));   // beyond d_stop + beta
    EXPECT_FALSE(area.contains({0.5, 0.4}));   // beside the swept corridor
    EXPECT_FALSE(area.contains({-0.1, 0.0}));  // behind
    // A point that makes obs_cur 0 also changes the non-blocked area (the
    // corner of the rectangle included), and one outside does neither.
    const double empty = nonBlockedArea({}, area);
    EXPECT_NEAR(empty, 181 * 0.85, 1e-9);
    for (const mrpt::math::TPoint2D p :
         {mrpt::math::TPoint2D{0.84, 0.34}, mrpt::math::TPoint2D{0.3, -0.3},
          mrpt::math::TPoint2D{0.6, 0.0}}) {
        EXPECT_EQ(obsCur({p}, area), 0);
        EXPECT_LT(nonBlockedArea({p}, area), empty - 1e-6) << p.x << " " << p.y;
    }
    for (const mrpt::math::TPoint2D p :
         {mrpt::math::TPoint2D{0.86, 0.0}, mrpt::math::TPoint2D{0.5, 0.36}}) {
        EXPECT_EQ(obsCur({p}, area), 1);
        EXPECT_EQ(nonBlockedArea({p}, area), empty);
    }
}

TEST(AfraidFunctions, NonBlockedAreaIsTheFreeLengthAlongEachDirection) {
    const TCollisionArea area{0.85, 0.35};
    // A point straight ahead at 0.6 m blocks the directions it lies within
    // 0.35 m of (|dtheta| <= asin(0.35 / 0.6) = 35.7 deg), each reaching
    // 0.6 cos(dtheta) instead of 0.85.
    double expected = 0;
    for (int i = 0; i < 181; i++) {
        const double th = -M_PI / 2 + M_PI * i / 180;
        expected += std::abs(0.6 * std::sin(th)) <= 0.35 && std::cos(th) > 0
                        ? std::min(0.85, 0.6 * std::cos(th))
                        : 0.85;
    }
    EXPECT_NEAR(nonBlockedArea({{0.6, 0.0}}, area), expected, 1e-9);
    // Closer blocks more; the difference is a fraction of the whole area.
    const double a6 = nonBlockedArea({{0.6, 0.0}}, area);
    const double a4 = nonBlockedArea({{0.4, 0.0}}, area);
    EXPECT_LT(a4, a6);
    EXPECT_NEAR(areaDifference(181 * 0.85, a4, area), (181 * 0.85 - a4) / (181 * 0.85),
                1e-12);
    EXPECT_GT(areaDifference(181 * 0.85, a4, area), 0.05);
}

namespace {
using mrpt::math::TPose2D;
const mrpt::math::CMatrixDouble33 kPerfect;  // zero covariance: a perfect pose

// A 3 m wide corridor along x (walls at y = -1.5 and +1.5), x from -2 to 18 m;
// deadEnd: a wall across it at x = 6.
mrpt::maps::COccupancyGridMap2D corridor(bool deadEnd = false) {
    mrpt::maps::COccupancyGridMap2D g(-2, 18, -2.5, 2.5, 0.05f);
    g.fill(1.0f);
    for (unsigned cy = 0; cy < g.getSizeY(); cy++)
        for (unsigned cx = 0; cx < g.getSizeX(); cx++)
            if (std::abs(g.idx2y(cy)) > 1.5 || (deadEnd && g.idx2x(cx) > 6.0))
                g.setCell(cx, cy, 0.0f);
    return g;
}

struct TWorld {
    mrpt::maps::COccupancyGridMap2D map;
    risknav::mapping::CDistanceField field;
    explicit TWorld(bool deadEnd = false) : map(corridor(deadEnd)) {
        risknav::mapping::TObstacleRule rule;
        rule.outside_is_obstacle = false;
        field = risknav::mapping::CDistanceField(map, rule);
    }
};

// The laser scan of a robot at `truth` in the map, plus person discs
// (radius 0.25 m) at world positions.
mrpt::obs::CObservation2DRangeScan scanAt(
    const TWorld& w, const TPose2D& truth,
    std::vector<mrpt::math::TPoint2D> persons = {}) {
    mrpt::obs::CObservation2DRangeScan s;
    s.aperture = float(M_PI);
    s.maxRange = 8;
    s.rightToLeft = true;
    s.sensorPose = mrpt::poses::CPose3D(0.2, 0, 0.3, 0, 0, 0);
    w.map.laserScanSimulator(s, mrpt::poses::CPose2D(truth), 0.5f, 181, 0.0f);
    const mrpt::poses::CPose2D sensor =
        mrpt::poses::CPose2D(truth) + mrpt::poses::CPose2D(0.2, 0, 0);
    for (const auto& p : persons)
        for (size_t i = 0; i < 181; i++) {
            const double a = sensor.phi() - M_PI / 2 + M_PI * i / 180, dx = std::cos(a),
                         dy = std::sin(a);
            const double fx = sensor.x() - p.x, fy = sensor.y() - p.y,
                         b = fx * dx + fy * dy, c = fx * fx + fy * fy - 0.25 * 0.25;
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

TAfraidStep stepAt(CAfraidDetector& d, const TWorld& w, const TPose2D& truth,
                   std::vector<mrpt::math::TPoint2D> persons = {}, double speed = 0.2,
                   const TPose2D* believed = nullptr,
                   const mrpt::math::CMatrixDouble33& cov = kPerfect) {
    return d.step(scanAt(w, truth, persons), believed ? *believed : truth, cov, speed,
                  w.map, w.field);
}
}  // namespace

TEST(CAfraidDetector, EmptyCorridorMatchesTheMap) {
    const TWorld w;
    CAfraidDetector d;
    for (int k = 0; k < 10; k++) {
        const auto st = stepAt(d, w, {0.1 * k, 0, 0});
        EXPECT_NEAR(st.actualArea, st.expectedArea, 1e-9);
        EXPECT_NEAR(st.diff, 0.0, 1e-9);
        EXPECT_FALSE(st.afraid);
        EXPECT_EQ(st.obsCur, 1);
    }
}

TEST(CAfraidDetector, PersonSteppingIntoTheCollisionArea) {
    const TWorld w;
    CAfraidDetector d;
    for (int k = 0; k < 6; k++)
        stepAt(d, w, {0, 0, 0});                            // clear so far
    const auto st = stepAt(d, w, {0, 0, 0}, {{0.8, 0.1}});  // suddenly 0.8 m ahead
    EXPECT_EQ(st.obsCur, 0);
    EXPECT_EQ(st.obsPredict, 1);
    EXPECT_GT(st.diff, d.options.diff_threshold);
    EXPECT_TRUE(st.afraid);
    ASSERT_TRUE(st.obstacleFound);
    EXPECT_NEAR(st.obstacleX, 0.8 - 0.25, 0.05);  // the person's near edge
    // Still there next frame: now tracked, no second event.
    EXPECT_FALSE(stepAt(d, w, {0, 0, 0}, {{0.78, 0.1}}).afraid);
}

TEST(CAfraidDetector, PersonEnteringFromTheSideIsOneEvent) {
    // The person walks sideways into the robot's way 0.75 m ahead: it touches
    // the edge of the collision area first. One event, not zero (the old
    // rectangle-vs-circle geometry lost it) and not several.
    const TWorld w;
    CAfraidDetector d;
    int events = 0;
    for (int k = 0; k < 20; k++)
        events += stepAt(d, w, {0, 0, 0}, {{0.75, 1.0 - 0.08 * k}}, 0.2).afraid;
    EXPECT_EQ(events, 1);
}

TEST(CAfraidDetector, BrakingOrStandingRobotStillSeesThePerson) {
    const TWorld w;
    // Braking from 0.8 m/s: the person appears 1.4 m ahead while the speed
    // already reads 0.1 m/s (d_stop would be 0.1 m: area 0.75 m). The area
    // keeps d_stop of the recent 0.8 m/s (1.04 m: area 1.69 m).
    CAfraidDetector d;
    for (double v : {0.8, 0.8, 0.8, 0.5})
        stepAt(d, w, {0, 0, 0}, {}, v);
    const auto st = stepAt(d, w, {0, 0, 0}, {{1.4, 0.0}}, 0.1);
    EXPECT_TRUE(st.afraid);
    EXPECT_NEAR(st.dStop, 1.04, 1e-9);
    // A robot that has stood for a while: its area is radius + beta (0.65 m);
    // a person stepping in 0.6 m ahead is an event.
    CAfraidDetector standing;
    for (int k = 0; k < 10; k++)
        stepAt(standing, w, {0, 0, 0}, {}, 0.0);
    EXPECT_TRUE(stepAt(standing, w, {0, 0, 0}, {{0.85, 0.0}}, 0.0).afraid);
}

TEST(CAfraidDetector, DeadEndWallIsExplainedByTheMapNotAnEvent) {
    // The robot drives up to a mapped wall: the wall enters the collision area
    // (obs_cur = 0) but E_area, the map's prediction, explains it.
    const TWorld w(true);
    CAfraidDetector d;
    bool wallInside = false;
    double diffWithoutMap = 0;
    for (int k = 0; k < 40; k++) {
        const TPose2D pose{4.5 + 0.04 * k, 0, 0};
        const auto scan = scanAt(w, pose);
        const auto st = d.step(scan, pose, kPerfect, 0.2, w.map, w.field);
        EXPECT_FALSE(st.afraid) << k;
        wallInside |= st.obsCur == 0;
        // The same frame with E_area replaced by a constant (an empty area):
        // the wall alone would exceed the threshold.
        diffWithoutMap = std::max(
            diffWithoutMap,
            areaDifference(
                181 * st.area.length,
                nonBlockedArea(risknav::mapping::scanToRobotFrame(scan), st.area),
                st.area));
    }
    EXPECT_TRUE(wallInside);
    EXPECT_GT(diffWithoutMap, d.options.diff_threshold);
}

TEST(CAfraidDetector, LocalizationErrorIsNotAnEvent) {
    // Near the dead end the pose estimate is 0.16 m off along the corridor
    // (too close, as seen with MCL and pf-localization, or too far) and 5 deg
    // off; its covariance says 0.05 m and 2 deg. The wall it sees is the
    // map's wall.
    const TWorld w(true);
    mrpt::math::CMatrixDouble33 cov;
    cov(0, 0) = cov(1, 1) = 0.05 * 0.05;
    cov(2, 2) = std::pow(2 * M_PI / 180, 2);
    for (double off : {0.16, -0.16}) {
        int withCov = 0, noTolerance = 0;
        CAfraidDetector a, b;
        b.options.unexpected_margin = 0;  // no tolerance: the error is an obstacle
        for (int k = 0; k < 30; k++) {
            const TPose2D truth{4.6 + 0.04 * k, 0, 0},
                believed{4.6 + off + 0.04 * k, 0.05, 5 * M_PI / 180};
            withCov += stepAt(a, w, truth, {}, 0.2, &believed, cov).afraid;
            noTolerance += stepAt(b, w, truth, {}, 0.2, &believed, kPerfect).afraid;
        }
        EXPECT_EQ(withCov, 0) << off;
        EXPECT_GT(noTolerance, 0) << off;
    }
    // A real person at the dead end is still an event with that pose error.
    CAfraidDetector c;
    const TPose2D truth{4.6, 0, 0}, believed{4.76, 0.05, 5 * M_PI / 180};
    for (int k = 0; k < 6; k++)
        stepAt(c, w, truth, {}, 0.2, &believed, cov);
    EXPECT_TRUE(stepAt(c, w, truth, {{5.3, 0.0}}, 0.2, &believed, cov).afraid);
}

TEST(CAfraidDetector, PersonWalkingAlongTheCorridorFarAhead) {
    const TWorld w;
    CAfraidDetector d;
    for (int k = 0; k < 20; k++) {
        // 3 m ahead, off-centre, walking past: never within the collision area.
        const auto st = stepAt(d, w, {0, 0, 0}, {{3.0 - 0.1 * k, 0.8}});
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
