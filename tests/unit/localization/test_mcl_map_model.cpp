// CRawlogMcl's observation model on the map (obstacleRule: the cells the
// laser echoes from, their surfaces) and the lost check's convergence grace
// after initialize() / recover().
#include <risknav/localization/CRawlogMcl.h>

#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CActionRobotMovement2D.h>

#include <cmath>

using namespace risknav::localization;
using risknav::mapping::TObstacleRule;

namespace {
using Grid = mrpt::maps::COccupancyGridMap2D;

// The grid a simulated laser casts its rays on under `rule` (as the
// simulator's CRayCastMap): obstacles P(free) 0, everything else 1.
Grid echoing(const Grid& g, const TObstacleRule& rule) {
    Grid e(g);
    for (unsigned x = 0; x < g.getSizeX(); x++)
        for (unsigned y = 0; y < g.getSizeY(); y++)
            e.setCell(int(x), int(y),
                      rule.isObstacle(g.getCell(int(x), int(y))) ? 0.0f : 1.0f);
    return e;
}

// A 180 deg, 181-ray scan with 0.01 m noise (seeded by the caller's
// generator state) at `pose` on `echo`, reaching maxRange.
mrpt::obs::CObservation2DRangeScan::Ptr scanOn(const Grid& echo,
                                               const mrpt::math::TPose2D& pose,
                                               float maxRange = 10.0f) {
    auto s = mrpt::obs::CObservation2DRangeScan::Create();
    s->aperture = float(M_PI);
    s->maxRange = maxRange;
    s->rightToLeft = true;
    s->sensorPose = mrpt::poses::CPose3D(0.2, 0, 0.3, 0, 0, 0);
    s->sensorLabel = "LASER";
    echo.laserScanSimulator(*s, mrpt::poses::CPose2D(pose), 0.5f, 181, 0.01f);
    return s;
}

struct TFrame {
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CSensoryFrame sf;
};
// The robot stands still: zero odometry (MRPT's Gaussian model), one scan.
TFrame standing(const mrpt::obs::CObservation2DRangeScan::Ptr& scan) {
    TFrame f;
    mrpt::obs::CActionRobotMovement2D mv;
    mv.computeFromOdometry(mrpt::poses::CPose2D(0, 0, 0),
                           mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    f.acts.insert(mv);
    f.sf.insert(scan);
    return f;
}

CRawlogMcl filterAt(const mrpt::math::TPose2D& p, double halfXY, double halfPhiDeg,
                    int particles) {
    CRawlogMcl m;
    m.options.init = "pose";
    m.options.initPose = p;
    m.options.init_xy = m.options.init_y = halfXY;
    m.options.init_phi_deg = halfPhiDeg;
    m.options.particles = particles;
    return m;
}

// A 10 x 10 m room whose 0.2 m walls and 1 x 3 m block are grey, P(free)
// 0.55: unknown by the default rule (occupancy 0.45, between 0.35 and 0.65),
// as the outside of a SLAM map. With unknown_is_obstacle the laser echoes
// on them; MRPT's likelihood field (P(free) < 0.5) and the fit (occupancy
// >= 0.65) do not count them.
Grid greyRoom() {
    Grid g(0, 10, 0, 10, 0.05);
    g.fill(1.0f);
    for (unsigned x = 0; x < g.getSizeX(); x++)
        for (unsigned y = 0; y < g.getSizeY(); y++) {
            const double wx = g.idx2x(x), wy = g.idx2y(y);
            if (wx < 0.2 || wy < 0.2 || wx > 9.8 || wy > 9.8 ||
                (wx > 6 && wx < 7 && wy > 2 && wy < 5))
                g.setCell(int(x), int(y), 0.55f);
        }
    return g;
}

const mrpt::math::TPose2D kTruth(2.5, 3.0, 30 * M_PI / 180);
}  // namespace

// With the world's rule the filter expects returns where the laser gets them:
// at the true pose the scan fits and the filter is never judged lost. Without
// it (the grid as it is) the same scans fit nowhere: every check fails.
TEST(MclMapModel, GreyCellsTheLaserEchoesFromAreWalls) {
    const auto g = greyRoom();
    const TObstacleRule rule;  // unknown_is_obstacle, as [World]'s default
    const auto f = standing(scanOn(echoing(g, rule), kTruth));
    auto run = [&](bool withRule, double& minFit, int& failed) {
        auto m = filterAt(kTruth, 0.2, 10, 2000);
        if (withRule)
            m.obstacleRule = rule;
        m.initialize(g, 1);
        minFit = 1;
        failed = 0;
        for (int k = 0; k < 6; k++) {
            m.step(f.acts, f.sf);
            const auto c = m.checkLost(f.sf);
            minFit = std::min(minFit, c.fitFraction);
            failed += c.failed;
        }
        return m.estimate().mean;
    };
    double minFit = 0;
    int failed = 0;
    const auto mean = run(true, minFit, failed);
    EXPECT_GE(minFit, 0.9);
    EXPECT_EQ(failed, 0);
    EXPECT_NEAR(mean.x, kTruth.x, 0.1);
    EXPECT_NEAR(mean.y, kTruth.y, 0.1);
    run(false, minFit, failed);
    EXPECT_LT(minFit, 0.1);
    EXPECT_EQ(failed, 6);
}

// The rule's ring: with outside_is_obstacle the map's edge echoes (the
// simulator puts a wall there), and the model has it one cell outside.
TEST(MclMapModel, OutsideIsObstacleAddsTheRing) {
    Grid g(0, 4, 0, 4, 0.05);
    g.fill(1.0f);
    TObstacleRule rule;
    CRawlogMcl m = filterAt({2, 2, 0}, 0.5, 180, 1000);
    m.obstacleRule = rule;
    m.initialize(g, 1);
    const auto& e = *m.map();
    EXPECT_EQ(e.getSizeX(), g.getSizeX() + 2);
    EXPECT_NEAR(e.getXMin(), -0.05, 1e-6);
    EXPECT_LT(e.getPos(-0.025, 2.0), 0.01f);  // the ring
    EXPECT_GT(e.getPos(0.025, 2.0), 0.99f);   // the map's own edge cell, free
    rule.outside_is_obstacle = false;
    m.obstacleRule = rule;
    m.initialize(g, 1);
    EXPECT_EQ(m.map()->getSizeX(), g.getSizeX());
    // no rule: the grid as it is
    m.obstacleRule.reset();
    m.initialize(g, 1);
    EXPECT_EQ(m.map()->getSizeX(), g.getSizeX());
}

namespace {
// A 10 x 8 m map whose southern half (y < 4 m) is solid, as a SLAM map's
// unknown outside under unknown_is_obstacle; free above it.
Grid solidSouth() {
    Grid g(0, 10, 0, 8, 0.05);
    g.fill(1.0f);
    for (unsigned x = 0; x < g.getSizeX(); x++)
        for (unsigned y = 0; y < g.getSizeY(); y++)
            if (g.idx2y(y) < 4.0)
                g.setCell(int(x), int(y), 0.5f);
    return g;
}
// 1 m from the solid region's face, facing it; the laser (3 m) sees its
// face only.
const mrpt::math::TPose2D kFacing(5.0, 5.2, -M_PI / 2);
}  // namespace

// A return comes from an obstacle's surface: a pose 0.3 m nearer the face,
// which puts every return 0.3 m inside the solid region, is less likely
// than the true one (MRPT's field, counting every obstacle cell, rated both
// the same: a point inside an obstacle is at distance 0 from one).
TEST(MclMapModel, ReturnsInsideASolidRegionDoNotFit) {
    const auto g = solidSouth();
    const TObstacleRule rule;
    const auto scan = scanOn(echoing(g, rule), kFacing, 3.0f);
    auto m = filterAt({5, 6, 0}, 0.5, 180, 1000);
    m.obstacleRule = rule;
    m.initialize(g, 1);
    const mrpt::poses::CPose3D truth(
        mrpt::poses::CPose2D(kFacing.x, kFacing.y, kFacing.phi));
    const mrpt::poses::CPose3D inside(
        mrpt::poses::CPose2D(kFacing.x, kFacing.y - 0.3, kFacing.phi));
    const double llTruth = m.map()->computeObservationLikelihood(*scan, truth);
    const double llInside = m.map()->computeObservationLikelihood(*scan, inside);
    EXPECT_GT(llTruth - llInside, 5.0) << llTruth << " " << llInside;

    // The filter, started +-0.5 m about the truth, settles on it, not in
    // between it and the poses that look into the solid region.
    auto f = filterAt(kFacing, 0.5, 5, 5000);
    f.obstacleRule = rule;
    f.initialize(g, 1);
    const auto fr = standing(scan);
    for (int k = 0; k < 8; k++)
        f.step(fr.acts, fr.sf);
    EXPECT_NEAR(f.estimate().mean.y, kFacing.y, 0.05);
}

// After recover() the particles are spread over +-recovery_xy: the filter is
// converging, and its checks do not fail until its spread has first come
// within the bounds (before, three spread checks in a row judged it lost
// again and re-spread it, before its scans could pick the robot out). Here
// the laser sees nothing for the first 4 frames after the recovery (as in
// the open, or with a person in front of it), then the room.
TEST(LostDetection, ARecoveredFilterConvergesBeforeItIsJudged) {
    const auto g = greyRoom();
    const TObstacleRule rule;
    const auto echo = echoing(g, rule);
    const auto blind = standing(scanOn(echo, kTruth, 0.5f));  // no returns
    const auto f = standing(scanOn(echo, kTruth));
    auto m = filterAt(kTruth, 0.1, 5, 2000);
    m.obstacleRule = rule;
    m.initialize(g, 1);
    m.recover();
    int converging = 0, failed = 0;
    TLocalizationCheck c;
    for (int k = 0; k < 12; k++) {
        const auto& fr = k < 4 ? blind : f;
        m.step(fr.acts, fr.sf);
        c = m.checkLost(fr.sf);
        converging += c.converging;
        failed += c.failed;
        EXPECT_FALSE(c.lost) << k << " " << c.reason;
    }
    EXPECT_GE(converging, 4);  // the re-spread cloud is no estimate at first
    EXPECT_EQ(failed, 0);
    EXPECT_FALSE(c.converging);
    EXPECT_NEAR(m.estimate().mean.x, kTruth.x, 0.1);
    EXPECT_NEAR(m.estimate().mean.y, kTruth.y, 0.1);
}

// A filter that never converges (its laser sees nothing: every particle
// alike) is lost once converge_checks checks have passed since the reset.
TEST(LostDetection, AFilterThatDoesNotConvergeIsLostAfterTheGrace) {
    Grid g(0, 10, 0, 10, 0.05);
    g.fill(1.0f);
    const auto f = standing(scanOn(g, {5, 5, 0}, 2.0f));  // no returns
    auto m = filterAt({5, 5, 0}, 2, 180, 5000);
    m.lostOptions.converge_checks = 5;
    m.initialize(g, 1);
    for (int k = 1; k <= 5; k++) {
        m.step(f.acts, f.sf);
        const auto c = m.checkLost(f.sf);
        EXPECT_EQ(c.converging, k < 5) << k;
        EXPECT_EQ(c.lost, k == 5) << k;
        if (k == 5) {
            EXPECT_EQ(c.reason, "not_converged");
        }
    }
}

// loadFromConfigFile() takes the rule from [World] when the config has it.
TEST(MclMapModel, RuleIsReadFromWorld) {
    mrpt::config::CConfigFileMemory c;
    c.write("Localization", "particles", "5000");
    CRawlogMcl m;
    m.loadFromConfigFile(c);
    EXPECT_FALSE(m.obstacleRule.has_value());
    c.write("World", "unknown_is_obstacle", "false");
    c.write("World", "occupied_threshold", "0.7");
    m.loadFromConfigFile(c);
    ASSERT_TRUE(m.obstacleRule.has_value());
    EXPECT_FALSE(m.obstacleRule->unknown_is_obstacle);
    EXPECT_TRUE(m.obstacleRule->outside_is_obstacle);
    EXPECT_DOUBLE_EQ(m.obstacleRule->occupied_threshold, 0.7);
}

// The default recovery draws as densely per KLD bin as the default start set
// does, and at least CRawlogMcl's documented minimum.
TEST(LostDetection, DefaultRecoveryCoversItsBoxAsTheStartSetDoes) {
    const CRawlogMcl m;
    const auto& o = m.lostOptions;
    const auto& k = m.kldOptions;
    const double heading = std::min(2 * M_PI, 2 * o.recovery_phi_deg * M_PI / 180);
    const double bins =
        std::pow(2 * o.recovery_xy / k.KLD_binSize_XY, 2) * heading / k.KLD_binSize_PHI;
    const double startBins = std::pow(2 * m.options.init_xy / k.KLD_binSize_XY, 2) *
                             std::min(2 * M_PI, 2 * m.options.init_phi_deg * M_PI / 180) /
                             k.KLD_binSize_PHI;
    EXPECT_GE(o.recovery_particles / bins, CRawlogMcl::kMinParticlesPerBin);
    EXPECT_GE(o.recovery_particles / bins, 0.99 * m.options.particles / startBins);
}
