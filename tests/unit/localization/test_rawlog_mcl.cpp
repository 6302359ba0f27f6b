#include <risknav/common/CBadInputError.h>
#include <risknav/common/grid_io.h>
#include <risknav/localization/CRawlogMcl.h>
#include <risknav/localization/CRawlogReader.h>
#include <risknav/localization/scan_fit.h>

#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CActionRobotMovement2D.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>

#include "test_support.h"

using namespace risknav::localization;
using risknav::common::CConfigKeyError;

namespace {
// A 10 x 10 m map at 0.05 m, all free but an occupied 2 x 10 m band at x in
// [8, 10] (default KLD bins: 0.10 m x 10 deg).
mrpt::maps::COccupancyGridMap2D makeMap() {
    mrpt::maps::COccupancyGridMap2D g(0, 10, 0, 10, 0.05);
    g.fill(1.0f);
    for (int x = g.x2idx(8.0); x < int(g.getSizeX()); x++)
        for (unsigned y = 0; y < g.getSizeY(); y++)
            g.setCell(x, int(y), 0.0f);
    return g;
}

CRawlogMcl poseMcl(double x, double y, double halfXY, double halfPhiDeg, int particles) {
    CRawlogMcl m;
    m.options.init = "pose";
    m.options.initPose = {x, y, 0};
    m.options.init_xy = m.options.init_y = halfXY;
    m.options.init_phi_deg = halfPhiDeg;
    m.options.particles = particles;
    return m;
}
}  // namespace

// The initial region in KLD bins: free area / binXY^2 x heading range / binPHI.
TEST(RawlogMclParticles, InitialRegionInKldBins) {
    const auto g = makeMap();
    // A free 2 x 2 m box, any heading: 41 x 41 cells (both ends included,
    // as resetUniformFreeSpace() draws), 420.25 x 36 bins.
    const double box = 41 * 41 * 0.05 * 0.05 / (0.1 * 0.1);
    EXPECT_NEAR(poseMcl(4, 5, 1, 180, 5000).initialBins(g), box * 36, 1e-3);
    // Half the box on the occupied band: 20 x 41 free cells.
    EXPECT_NEAR(poseMcl(8, 5, 1, 180, 5000).initialBins(g), 20 * 41 * 0.25 * 36, 1e-3);
    // +-10 deg: 2 heading bins.
    EXPECT_NEAR(poseMcl(4, 5, 1, 10, 5000).initialBins(g), box * 2, 1e-3);
    // A point and one heading: one bin.
    EXPECT_DOUBLE_EQ(poseMcl(4, 5, 0, 0, 10).initialBins(g), 1.0);
    // Global: every free cell (x < 8 m), any heading.
    auto m = poseMcl(4, 5, 1, 10, 5000);
    m.options.init = "global";
    const double cells = g.x2idx(8.0) * 200.0;
    EXPECT_NEAR(m.initialBins(g), cells * 0.25 * 36, 0.1);
    // Coarser bins, fewer of them.
    m.kldOptions.KLD_binSize_XY = 0.2;
    EXPECT_NEAR(m.initialBins(g), cells / 16 * 36, 0.1);
}

// Too few start particles for the region: refused naming the key and the bound.
TEST(RawlogMclParticles, TooFewForTheInitialRegionAreRefused) {
    const auto g = makeMap();
    auto m = poseMcl(4, 5, 1, 180, 200);
    const int n = m.minParticles(g);
    EXPECT_EQ(n, int(std::ceil(CRawlogMcl::kMinParticlesPerBin * 420.25 * 36)));
    try {
        m.checkParticles(g);
        FAIL() << "200 particles for 14400 bins accepted";
    } catch (const CConfigKeyError& e) {
        EXPECT_EQ(e.section, "Localization");
        EXPECT_EQ(e.key, "particles");
        EXPECT_EQ(e.value, "200");
        EXPECT_NE(e.rule.find("must be in [" + std::to_string(n) + ", 1e+06]"),
                  std::string::npos)
            << e.rule;
    }
    m.options.particles = n;
    EXPECT_NO_THROW(m.checkParticles(g));
    m.options.particles = n - 1;
    EXPECT_THROW(m.checkParticles(g), CConfigKeyError);
    // Global over the whole map needs more.
    m.options.init = "global";
    m.options.particles = n;
    EXPECT_THROW(m.checkParticles(g), CConfigKeyError);
}

// A small box needs few: the documented minimum of 10 holds there.
TEST(RawlogMclParticles, SmallRegionTakesTheDocumentedMinimum) {
    const auto g = makeMap();
    EXPECT_EQ(poseMcl(4, 5, 0, 0, 10).minParticles(g), 10);
    EXPECT_NO_THROW(poseMcl(4, 5, 0.1, 5, 10).checkParticles(g));
}

// ---- Lost-localization detection (CRawlogMcl::checkLost, judgeLocalization,
// scanMapFit) ----

namespace {
// A 10 x 10 m room with 0.2 m walls and a 1 x 3 m block at x in [6, 7],
// y in [2, 5]: no two poses 3 m apart see the same scan.
mrpt::maps::COccupancyGridMap2D makeRoom() {
    mrpt::maps::COccupancyGridMap2D g(0, 10, 0, 10, 0.05);
    g.fill(1.0f);
    for (unsigned x = 0; x < g.getSizeX(); x++)
        for (unsigned y = 0; y < g.getSizeY(); y++) {
            const double wx = g.idx2x(x), wy = g.idx2y(y);
            const bool wall = wx < 0.2 || wy < 0.2 || wx > 9.8 || wy > 9.8;
            const bool block = wx > 6 && wx < 7 && wy > 2 && wy < 5;
            if (wall || block)
                g.setCell(int(x), int(y), 0.0f);
        }
    return g;
}

// A 180 deg, 181-ray scan the map's own ray casting gives at `pose`.
mrpt::obs::CObservation2DRangeScan::Ptr scanAt(const mrpt::maps::COccupancyGridMap2D& g,
                                               const mrpt::math::TPose2D& pose) {
    auto s = mrpt::obs::CObservation2DRangeScan::Create();
    s->aperture = float(M_PI);
    s->maxRange = 20.0f;
    s->rightToLeft = true;
    s->sensorPose = mrpt::poses::CPose3D(0, 0, 0.3, 0, 0, 0);
    s->sensorLabel = "LASER";
    g.laserScanSimulator(*s, mrpt::poses::CPose2D(pose), 0.5f, 181, 0.01f);
    return s;
}

// The robot's pose, and one 3 m from it (2.1 m east and north).
const mrpt::math::TPose2D kTruth(2.5, 3.0, 30 * M_PI / 180);
const mrpt::math::TPose2D kOff(kTruth.x + 3 / M_SQRT2, kTruth.y + 3 / M_SQRT2,
                               kTruth.phi);

struct TFrame {
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CSensoryFrame sf;
};
// The robot stands still: zero odometry (MRPT's Gaussian model), one scan.
TFrame standingFrame(const mrpt::obs::CObservation2DRangeScan::Ptr& scan) {
    TFrame f;
    mrpt::obs::CActionRobotMovement2D mv;
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions mm;
    mv.computeFromOdometry(mrpt::poses::CPose2D(0, 0, 0), mm);
    f.acts.insert(mv);
    f.sf.insert(scan);
    return f;
}
}  // namespace

// The scan-to-map fit: every point on a wall at the true pose, few 3 m off
// (diagonally: shifted along a wall, that wall's points would still fit); a
// point off the map counts and does not fit; max range leaves points out.
TEST(ScanMapFit, AtTheTruePoseEveryPointFitsThreeMetresOffFew) {
    const auto g = makeRoom();
    risknav::mapping::TObstacleRule rule;
    rule.unknown_is_obstacle = rule.outside_is_obstacle = false;
    const risknav::mapping::CDistanceField field(g, rule);
    const auto scan = scanAt(g, kTruth);
    const auto at = scanMapFit(field, *scan, kTruth, 0.25);
    EXPECT_EQ(at.points, 181u);
    EXPECT_EQ(at.onMap, 181u);
    EXPECT_GE(at.fraction(), 0.99);
    const auto off = scanMapFit(field, *scan, kOff, 0.25);
    EXPECT_EQ(off.points, 181u);
    EXPECT_LT(off.onMap, off.points);  // beyond the walls
    EXPECT_LT(off.fraction(), 0.3);
    // returns farther than 4 m from the sensor are not counted
    size_t within = 0;
    for (size_t i = 0; i < scan->getScanSize(); i++)
        within += scan->getScanRangeValidity(i) && scan->getScanRange(i) <= 4.0f;
    const auto near = scanMapFit(field, *scan, kTruth, 0.25, 4.0);
    EXPECT_EQ(near.points, within);
    EXPECT_GT(near.points, 0u);
    EXPECT_LT(near.points, at.points);
    // no points: no fraction
    EXPECT_TRUE(std::isnan(scanMapFit(field, *scan, kTruth, 0.25, 0.01).fraction()));
}

// The per-check rule, alone: fit, then spread in x y, then heading.
TEST(LostDetection, TheRuleNamesTheFirstFigureOutOfItsBound) {
    TLostDetectionOptions o;
    TScanFit good;
    good.points = good.onMap = 100;
    good.fitting = 90;
    auto c = judgeLocalization(good, 0.1, 2, o);
    EXPECT_FALSE(c.failed);
    EXPECT_FALSE(c.lost);
    EXPECT_EQ(c.reason, "");
    EXPECT_DOUBLE_EQ(c.fitFraction, 0.9);
    TScanFit bad = good;
    bad.fitting = 40;
    c = judgeLocalization(bad, 0.1, 2, o);
    EXPECT_TRUE(c.failed);
    EXPECT_TRUE(c.lost);  // alone, lost == failed
    EXPECT_EQ(c.reason, "scan_fit");
    // exactly min_fit fits
    bad.fitting = 50;
    EXPECT_FALSE(judgeLocalization(bad, 0.1, 2, o).failed);
    // too few points: the fit is not judged
    TScanFit few;
    few.points = few.onMap = 19;
    c = judgeLocalization(few, 0.1, 2, o);
    EXPECT_FALSE(c.fitJudged);
    EXPECT_FALSE(c.failed);
    EXPECT_TRUE(judgeLocalization(TScanFit{}, 0.1, 2, o).fitJudged == false);
    // spread
    EXPECT_EQ(judgeLocalization(good, 1.5, 2, o).reason, "spread_xy");
    EXPECT_EQ(judgeLocalization(good, 0.1, 45, o).reason, "spread_phi");
    EXPECT_EQ(judgeLocalization(good, std::nan(""), 2, o).reason, "spread_xy");
}

TEST(LostDetection, OptionsAreValidatedWithTheirKeys) {
    auto expectKey = [](const std::function<void(TLostDetectionOptions&)>& set,
                        const std::string& key) {
        TLostDetectionOptions o;
        o.section = "Lost";
        set(o);
        try {
            o.validate();
            FAIL() << key << " accepted";
        } catch (const CConfigKeyError& e) {
            EXPECT_EQ(e.section, "Lost");
            EXPECT_EQ(e.key, key);
        }
    };
    EXPECT_NO_THROW(TLostDetectionOptions().validate());
    expectKey([](auto& o) { o.fit_distance = 0; }, "fit_distance");
    expectKey([](auto& o) { o.min_fit = 1.5; }, "min_fit");
    expectKey([](auto& o) { o.max_range = -1; }, "max_range");
    expectKey([](auto& o) { o.min_points = 0; }, "min_points");
    expectKey([](auto& o) { o.max_spread_xy = 0; }, "max_spread_xy");
    expectKey([](auto& o) { o.max_spread_phi_deg = std::nan(""); }, "max_spread_phi_deg");
    expectKey([](auto& o) { o.lost_after = 0; }, "lost_after");
    expectKey([](auto& o) { o.recovery_xy = -2; }, "recovery_xy");
    expectKey([](auto& o) { o.recovery_phi_deg = 190; }, "recovery_phi_deg");
    expectKey([](auto& o) { o.recovery_particles = 5; }, "recovery_particles");
    // and the keys read back as written
    TLostDetectionOptions a;
    a.min_fit = 0.6;
    a.lost_after = 5;
    a.recovery_phi_deg = 30;
    mrpt::config::CConfigFileMemory mem;
    a.saveToConfigFile(mem, "Lost");
    TLostDetectionOptions b;
    b.loadFromConfigFile(mem, "Lost");
    EXPECT_EQ(b.min_fit, 0.6);
    EXPECT_EQ(b.lost_after, 5);
    EXPECT_EQ(b.recovery_phi_deg, 30);
    EXPECT_EQ(b.section, "Lost");
}

// A filter started at the robot's pose, fed the scan it sees there, is not lost.
TEST(LostDetection, AFilterAtTheTruePoseIsNotLost) {
    const auto g = makeRoom();
    auto m = poseMcl(kTruth.x, kTruth.y, 0.2, 10, 2000);
    m.options.initPose = kTruth;
    m.initialize(g, 1);
    const auto f = standingFrame(scanAt(g, kTruth));
    for (int k = 0; k < 6; k++) {
        m.step(f.acts, f.sf);
        const auto c = m.checkLost(f.sf);
        EXPECT_FALSE(c.failed) << k << " " << c.reason;
        EXPECT_FALSE(c.lost) << k;
        EXPECT_TRUE(c.fitJudged);
        EXPECT_GE(c.fitFraction, 0.9) << k;
        EXPECT_LT(c.spreadXY, 0.3) << k;
        EXPECT_EQ(c.consecutiveFailed, 0);
        EXPECT_GT(c.particles, 0u);
    }
}

// A filter whose particles all lie 3 m from the robot: its scan does not fit
// there; lost after lost_after checks in a row; recover() around the mean
// finds the robot again.
TEST(LostDetection, AFilterThreeMetresOffIsLostAndRecovers) {
    const auto g = makeRoom();
    auto m = poseMcl(kOff.x, kOff.y, 0.2, 10, 2000);
    m.options.initPose = kOff;
    m.initialize(g, 1);
    const auto f = standingFrame(scanAt(g, kTruth));
    for (int k = 0; k < 3; k++) {
        m.step(f.acts, f.sf);
        const auto c = m.checkLost(f.sf);
        EXPECT_TRUE(c.failed) << k;
        EXPECT_EQ(c.reason, "scan_fit") << k;
        EXPECT_LT(c.fitFraction, 0.5) << k;
        EXPECT_EQ(c.consecutiveFailed, k + 1);
        EXPECT_EQ(c.lost, k + 1 >= m.lostOptions.lost_after) << k;
    }
    // the standard recovery: particles re-spread over +-4 m around the mean
    m.lostOptions.recovery_xy = 4;
    m.lostOptions.recovery_particles = 20000;
    m.recover();
    TLocalizationCheck c;
    for (int k = 0; k < 10; k++) {
        m.step(f.acts, f.sf);
        c = m.checkLost(f.sf);
    }
    EXPECT_FALSE(c.failed) << c.reason;
    EXPECT_FALSE(c.lost);
    const auto e = m.estimate();
    EXPECT_NEAR(e.mean.x, kTruth.x, 0.2);
    EXPECT_NEAR(e.mean.y, kTruth.y, 0.2);
    // global recovery spreads over the whole map: not one estimate yet
    m.recover(true);
    c = m.checkLocalization(nullptr);
    EXPECT_TRUE(c.failed);
    EXPECT_EQ(c.reason, "spread_xy");
    EXPECT_EQ(c.particles, 20000u);
}

namespace {
const char* kDemoRawlog = "/usr/share/mrpt/datasets/localization_demo.rawlog";
mrpt::maps::COccupancyGridMap2D demoMap() {
    risknav::common::TMapSourceOptions src;
    src.map_file = "/usr/share/mrpt/datasets/localization_demo.simplemap.gz";
    return risknav::common::loadOccupancyGrid(src);
}
}  // namespace

// MRPT's real log and map (localization_demo: 37 frames, 13 m of an office
// floor), localized as MRPT's own localization_demo.ini starts it (40000
// particles over x in [-10, 10], y in [-15, -5], any heading): while the
// particles are still spread the filter is converging (its checks do not
// fail), then it has converged; no check fails, and it is never lost.
TEST(LostDetection, MrptLocalizationDemoIsNeverLostOnceLocalized) {
    const auto g = demoMap();
    CRawlogMcl m;
    m.options.particles = 40000;
    m.options.initPose = {0, -10, 0};
    m.options.init_xy = 10;
    m.options.init_y = 5;
    m.options.init_phi_deg = 180;
    m.initialize(g, 1);
    CRawlogReader reader(kDemoRawlog);
    int frames = 0, firstPassed = -1, lost = 0, failedAfter = 0;
    double minFit = 1, maxSpread = 0;
    while (const auto f = reader.next()) {
        if (!f->actions || !f->sf)
            continue;
        m.step(*f->actions, *f->sf);
        const auto c = m.checkLost(*f->sf);
        std::cout << "[localization_demo] frame " << frames << ": fit " << c.fitFraction
                  << " (" << c.fit.fitting << "/" << c.fit.points << "), spread "
                  << c.spreadXY << " m " << c.spreadPhiDeg << " deg, ess " << c.ess
                  << ", " << c.particles << " particles" << (c.failed ? " FAILED " : "")
                  << c.reason << "\n";
        if (!c.failed && firstPassed < 0)
            firstPassed = frames;
        if (firstPassed >= 0) {
            failedAfter += c.failed;
            lost += c.lost;
            minFit = std::min(minFit, c.fitFraction);
            maxSpread = std::max(maxSpread, c.spreadXY);
        }
        frames++;
    }
    EXPECT_EQ(frames, 37);
    ASSERT_GE(firstPassed, 0);
    EXPECT_LE(firstPassed, 5);
    EXPECT_EQ(failedAfter, 0);
    EXPECT_EQ(lost, 0);
    std::cout << "[localization_demo] localized from frame " << firstPassed
              << ", then fit >= " << minFit << ", spread <= " << maxSpread << " m\n";
}

// The same log, the filter started 3 m from where the demo's filter
// localizes the first frame, its particles within +-0.2 m and +-10 deg
// there. Across the corridor (3 m south) the real scans do not fit: lost at
// the lost_after-th frame. Along it (3 m east) most points still lie on the
// corridor's walls (fit 0.52-0.79 in the first frames, as the filter slides
// its particles along): the fit sees it only when the corridor's features
// come into view, here at frame 15 of 37 (the test's print). A limit of
// any scan-fit test, said in TLostDetectionOptions.
TEST(LostDetection, MrptLocalizationDemoStartedThreeMetresOffIsLost) {
    const auto g = demoMap();
    CRawlogMcl demo;
    demo.options.particles = 40000;
    demo.options.initPose = {0, -10, 0};
    demo.options.init_xy = 10;
    demo.options.init_y = 5;
    demo.options.init_phi_deg = 180;
    demo.initialize(g, 1);
    CRawlogReader first(kDemoRawlog);
    auto f = first.next();
    ASSERT_TRUE(f && f->actions && f->sf);
    const auto start = demo.step(*f->actions, *f->sf).mean;
    // the frame at which a filter started at (dx, dy) from there is lost
    auto lostAt = [&](double dx, double dy, const char* label) {
        EXPECT_GE(g.getPos(start.x + dx, start.y + dy), 0.7f) << label << ": not free";
        auto m = poseMcl(start.x + dx, start.y + dy, 0.2, 10, 2000);
        m.options.initPose.phi = start.phi;
        m.initialize(g, 1);
        CRawlogReader reader(kDemoRawlog);
        int frames = 0, at = -1;
        while (const auto fr = reader.next()) {
            if (!fr->actions || !fr->sf)
                continue;
            m.step(*fr->actions, *fr->sf);
            const auto c = m.checkLost(*fr->sf);
            std::cout << "[localization_demo, 3 m " << label << "] frame " << frames
                      << ": fit " << c.fitFraction << ", spread " << c.spreadXY << " m, "
                      << (c.failed ? c.reason : std::string("passed"))
                      << (c.lost ? ", LOST" : "") << "\n";
            if (c.lost && at < 0)
                at = frames;
            frames++;
        }
        return at;
    };
    const int across = lostAt(0, -3, "south");
    EXPECT_GE(across, 0);
    EXPECT_LE(across, CRawlogMcl().lostOptions.lost_after);
    const int along = lostAt(3, 0, "east");
    EXPECT_GE(along, 0);  // before the log ends
}

TEST(LostDetection, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    // config/risknav-navigate.ini documents [LostLocalization] commented out
    // (the section is refused unless localization = mcl): "; key = value"
    // lines from "; [LostLocalization]" to the blank line
    std::map<std::string, std::string> documented;
    bool in = false;
    for (const auto& line : risknav::test::readLines(
             risknav::test::sourcePath("config/risknav-navigate.ini"))) {
        if (line.rfind("; [LostLocalization]", 0) == 0)
            in = true;
        else if (in && line.rfind("; ", 0) != 0)
            break;
        else if (in && line.find('=') != std::string::npos) {
            std::istringstream l(line.substr(2));
            std::string key, eq, value;
            l >> key >> eq >> value;
            documented[key] = value;
        }
    }
    const auto keys = TLostDetectionOptions().keys();
    ASSERT_EQ(keys.size(), 11u);
    EXPECT_EQ(documented.size(), keys.size());
    for (const auto& k : keys) {
        ASSERT_TRUE(documented.count(k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        EXPECT_EQ(documented[k.key], k.defaultText) << k.key;
    }
}

TEST(RawlogMclOptions, TheDocumentedConfigHoldsEveryDeclaredKey) {
    mrpt::config::CConfigFileMemory doc(risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-afraid-learn.ini")));
    const CRawlogMcl::TOptions defaults;
    const auto keys = defaults.keys();
    ASSERT_EQ(keys.size(), 8u);
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists("Localization", k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        if (k.key == "init_pose" || k.key == "init_xy")
            continue;  // the example's box, not the default
        const std::string v = doc.read_string("Localization", k.key, "");
        EXPECT_EQ(v.substr(0, v.find_first_of(" \t/")), k.defaultText) << k.key;
    }
    // the heading in degrees in the file; init_xy one or two half-widths
    mrpt::config::CConfigFileMemory c(
        "[Localization]\ninit_pose = 1 2 90\ninit_xy = 3\n");
    CRawlogMcl::TOptions o;
    o.loadFromConfigFile(c, "Localization");
    EXPECT_NEAR(o.initPose.phi, M_PI / 2, 1e-15);
    EXPECT_EQ(o.init_xy, 3);
    EXPECT_EQ(o.init_y, 3);
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "Localization");
    CRawlogMcl::TOptions back;
    back.loadFromConfigFile(saved, "Localization");
    EXPECT_EQ(back.initPose, o.initPose);
    EXPECT_EQ(back.init_y, 3);
    for (const char* bad :
         {"[Localization]\ninit_pose = 1 2\n", "[Localization]\ninit_xy = 1 2 3\n"}) {
        CRawlogMcl m;
        EXPECT_THROW(m.loadFromConfigFile(mrpt::config::CConfigFileMemory(bad)),
                     risknav::common::CBadInputError)
            << bad;
    }
}
