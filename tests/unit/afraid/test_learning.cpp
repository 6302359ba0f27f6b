#include <risknav/afraid/CAfraidDetector.h>
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/afraid/CAfraidLearner.h>
#include <risknav/afraid/afraid_zones.h>
#include <risknav/afraid/ground_truth.h>
#include <risknav/afraid/kernel_regression.h>
#include <risknav/common/CBadInputError.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <set>

#include "test_support.h"

using namespace risknav::afraid;

TEST(KernelRegression, SparseSolveEqualsDenseReference) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int trial = 0; trial < 5; trial++) {
        std::vector<TKrrSample> s;
        for (int i = 0; i < 150; i++)
            s.push_back({u(rng) * 6, u(rng) * 3, u(rng) < 0.1 ? 1.0 : 0.0});
        TKrrOptions o;
        o.bandwidth = 0.3 + 0.2 * trial;
        o.lambda = 0.05 + 0.2 * trial;
        const auto a = krrFit(s, o), b = krrFitDense(s, o);
        ASSERT_EQ(a.size(), b.size());
        double maxDiff = 0, maxVal = 0;
        for (size_t i = 0; i < a.size(); i++) {
            maxDiff = std::max(maxDiff, std::abs(a[i] - b[i]));
            maxVal = std::max(maxVal, std::abs(b[i]));
        }
        EXPECT_LT(maxDiff, 1e-6 * std::max(1.0, maxVal)) << "trial " << trial;
        // The grid evaluation equals the pointwise one.
        const auto grid = krrPredictGrid(s, a, o, 0, 0, 0.1, 60, 30);
        for (int k = 0; k < 20; k++) {
            const int cx = int(u(rng) * 60), cy = int(u(rng) * 30);
            EXPECT_NEAR(grid[size_t(cy) * 60 + cx],
                        krrPredict(s, a, o, 0.05 + 0.1 * cx, 0.05 + 0.1 * cy), 1e-5);
        }
    }
}

TEST(KernelRegression, RecoversASmoothBump) {
    // Samples of a Gaussian bump: the fit reproduces it between the samples.
    std::vector<TKrrSample> s;
    for (double x = 0; x <= 10; x += 0.1)
        s.push_back({x, 0, std::exp(-std::pow(x - 5, 2) / 2)});
    TKrrOptions o;
    o.bandwidth = 0.5;
    o.lambda = 1e-3;
    const auto a = krrFit(s, o);
    for (double x = 1; x <= 9; x += 0.37)
        EXPECT_NEAR(krrPredict(s, a, o, x, 0), std::exp(-std::pow(x - 5, 2) / 2), 0.02);
}

namespace {
mrpt::maps::COccupancyGridMap2D smallMap() {
    mrpt::maps::COccupancyGridMap2D g(0, 10, 0, 4, 0.05f);
    g.fill(1.0f);
    return g;
}
}  // namespace

TEST(CAfraidGrid, SaveLoadMergeEqualsLearningOnBoth) {
    const auto map = smallMap();
    // "Rawlog" 1 and 2 as event/exposure streams; learning on both at once
    // must equal learning each and merging the saved files.
    CAfraidGrid both(map), one(map), two(map);
    auto feed = [](CAfraidGrid& g, int seed) {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(0, 1);
        for (int i = 0; i < 500; i++) {
            const double x = u(rng) * 10, y = 2 + 0.1 * u(rng);
            g.addExposure(x, y);
            if (u(rng) < 0.05) {
                g.addRobotEvent(x, y);
                g.addObstacleEvent(x + 0.5, y + 0.5);
            }
        }
        g.frames += 500;
        g.runs += 1;
    };
    feed(one, 1);
    feed(two, 2);
    feed(both, 1);
    feed(both, 2);
    const std::string d = risknav::test::freshDir("afraid");
    one.save(d + "/one.afraid");
    two.save(d + "/two.afraid");
    CAfraidGrid merged = CAfraidGrid::load(d + "/one.afraid");
    merged.merge(CAfraidGrid::load(d + "/two.afraid"));
    EXPECT_EQ(merged.exposure(), both.exposure());
    EXPECT_EQ(merged.robotEvents(), both.robotEvents());
    EXPECT_EQ(merged.obstacleEvents(), both.obstacleEvents());
    EXPECT_EQ(merged.runs, 2u);
    EXPECT_EQ(merged.frames, 1000u);
    EXPECT_GT(merged.totalRobotEvents(), 20u);
}

TEST(CAfraidGrid, BadFilesAndForeignGeometry) {
    const std::string d = risknav::test::freshDir("afraid");
    risknav::test::writeFile(d + "/text.afraid", "not an afraid file");
    EXPECT_THROW(CAfraidGrid::load(d + "/text.afraid"), std::runtime_error);
    EXPECT_THROW(CAfraidGrid::load(d + "/missing.afraid"), std::runtime_error);
    CAfraidGrid g(smallMap());
    g.save(d + "/ok.afraid");
    // Truncated: cut the (uncompressed-equivalent) stream short.
    const std::string full = risknav::test::readFile(d + "/ok.afraid");
    risknav::test::writeFile(d + "/cut.afraid", full.substr(0, full.size() / 2));
    EXPECT_THROW(CAfraidGrid::load(d + "/cut.afraid"), std::runtime_error);
    mrpt::maps::COccupancyGridMap2D other(0, 12, 0, 4, 0.05f);
    CAfraidGrid h(other);
    EXPECT_FALSE(g.sameGeometry(h));
    EXPECT_THROW(g.merge(h), std::runtime_error);
}

TEST(AfraidZones, ConnectedRegionsAndSpeedLimit) {
    const auto map = smallMap();
    CAfraidGrid g(map);
    std::vector<float> level(size_t(g.sizeX()) * g.sizeY(), 0.f);
    auto set = [&](double x0, double x1) {
        for (int cy = 30; cy < 50; cy++)
            for (int cx = g.xToCol(x0 + 1e-3); cx < g.xToCol(x1 + 1e-3); cx++)
                level[size_t(cy) * g.sizeX() + cx] = 0.3f;
    };
    set(2, 3);
    set(6, 7.5);
    const auto z = findZones(level, g, 0.1);
    ASSERT_EQ(z.size(), 2u);
    EXPECT_NEAR(z[0].xMin, 2, 1e-6);
    EXPECT_NEAR(z[0].xMax, 3, 1e-6);
    EXPECT_NEAR(z[1].area, 1.5 * 1.0, 1e-6);
    auto lv = [&](double x, double y) {
        const int cx = g.xToCol(x), cy = g.yToRow(y);
        return g.inside(cx, cy) ? double(level[size_t(cy) * g.sizeX() + cx]) : 0.0;
    };
    // d_stop(0.8) = 1.04 m: at x = 0.5 the zone (x >= 2) is out of reach, fast;
    // at x = 1.2 it is within the stopping distance ahead: already slow.
    EXPECT_DOUBLE_EQ(
        afraidSpeedLimit(lv, {{0.5, 2}, {9, 2}}, 0.8, 0.8, 0.2, 0.1, 0.9, 1.0), 0.8);
    EXPECT_DOUBLE_EQ(
        afraidSpeedLimit(lv, {{1.2, 2}, {9, 2}}, 0.8, 0.8, 0.2, 0.1, 0.9, 1.0), 0.2);
    EXPECT_DOUBLE_EQ(
        afraidSpeedLimit(lv, {{2.5, 2}, {9, 2}}, 0.8, 0.8, 0.2, 0.1, 0.9, 1.0), 0.2);
    EXPECT_DOUBLE_EQ(
        afraidSpeedLimit(lv, {{3.5, 2}, {9, 2}}, 0.8, 0.8, 0.2, 0.1, 0.9, 1.0), 0.8);
    // min with the behaviour's own speed.
    EXPECT_DOUBLE_EQ(
        afraidSpeedLimit(lv, {{3.5, 2}, {9, 2}}, 0.5, 0.8, 0.2, 0.1, 0.9, 1.0), 0.5);
}

// The learner's [AfraidLearn] options: set from code they run the same
// validate() as when read from a file; save/load round-trips (paths with
// spaces included).
TEST(CAfraidLearnerOptions, SetFromCodeAreValidatedAndRoundTrip) {
    using risknav::common::CConfigKeyError;
    const std::string d = risknav::test::freshDir("opts");
    risknav::test::writeFile(d + "/a b.rawlog", "x");
    risknav::test::writeFile(d + "/c.rawlog", "x");
    CAfraidLearner::TOptions o;
    o.map.map_file =
        risknav::test::sourcePath("datasets/corridor-doors/corridor.gridmap.gz");
    EXPECT_THROW(o.validate(), CConfigKeyError);  // no rawlog
    o.rawlogs = {d + "/a b.rawlog", d + "/c.rawlog"};
    EXPECT_NO_THROW(o.validate());
    o.v_safe = 1.0;  // > v_max
    try {
        o.validate();
        ADD_FAILURE() << "v_safe > v_max accepted";
    } catch (const CConfigKeyError& e) {
        EXPECT_EQ(e.key, "v_safe");
    }
    o.v_safe = 0.3;
    o.afraid_name = "x.txt";
    EXPECT_THROW(o.validate(), CConfigKeyError);
    o.afraid_name = "mine.afraid";
    o.krr.bandwidth = 0;
    EXPECT_THROW(o.validate(), CConfigKeyError);
    o.krr.bandwidth = 0.7;
    EXPECT_FALSE(o.obstacles.unknown_is_obstacle);  // the learner's default
    o.obstacles.unknown_is_obstacle = true;
    o.seed = 12345678901ULL;
    o.match_distance = 0.1 / 3;
    EXPECT_NO_THROW(o.validate());

    mrpt::config::CConfigFileMemory m;
    o.saveToConfigFile(m, "AfraidLearn");
    CAfraidLearner::TOptions r;
    r.loadFromConfigFile(m, "AfraidLearn");
    mrpt::config::CConfigFileMemory m2;
    r.saveToConfigFile(m2, "AfraidLearn");
    EXPECT_EQ(m.getContent(), m2.getContent());
    EXPECT_EQ(r.rawlogs, o.rawlogs);
    EXPECT_EQ(r.afraid_name, "mine.afraid");
    EXPECT_EQ(r.v_safe, 0.3);
    EXPECT_EQ(r.krr.bandwidth, 0.7);
    EXPECT_TRUE(r.obstacles.unknown_is_obstacle);
    EXPECT_FALSE(r.obstacles.outside_is_obstacle);
    EXPECT_EQ(r.seed, 12345678901ULL);
    EXPECT_EQ(r.match_distance, o.match_distance);
    EXPECT_NO_THROW(r.validate());
}

// readGroundTruth: risknav-simulate's "t x y phi" lines, strictly.
TEST(GroundTruthReader, ReadsSimulatorLinesAndNamesTheFirstBadLine) {
    const std::string dir = risknav::test::freshDir("unit_ground_truth");
    const std::string ok = dir + "/ok.txt";
    risknav::test::writeFile(ok,
                             "% t x y phi\n1600000000.0 2 4.5 0\n\n# pause\n1600000000.2 "
                             "2.0249 4.5 -1e-2\r\n");
    const auto gt = readGroundTruth(ok);
    ASSERT_EQ(gt.size(), 2u);
    EXPECT_DOUBLE_EQ(gt[1][0], 1600000000.2);
    EXPECT_DOUBLE_EQ(gt[1][1], 2.0249);
    EXPECT_DOUBLE_EQ(gt[1][3], -0.01);
    risknav::test::writeFile(dir + "/empty.txt", "% only a comment\n");
    EXPECT_TRUE(readGroundTruth(dir + "/empty.txt").empty());
    EXPECT_TRUE(readGroundTruth(dir + "/missing.txt").empty());
    // each bad line: file:line and what
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"0 1 2 3\n1 1 2 nan\n", "bad.txt:2: expected 't x y phi' (4 numbers)"},
        {"0 1 2 3\n1 1 2 inf\n", "bad.txt:2: expected"},
        {"0 1 2\n", "bad.txt:1: expected 't x y phi' (4 numbers), got '0 1 2'"},
        {"0 1 2 3 4\n", "bad.txt:1: expected"},
        {"0 1 2 0x10\n", "bad.txt:1: expected"},
        {"% c\n5 1 2 3\n5 1 2 3\n", "bad.txt:3: the times must increase"},
        {"5 1 2 3\n4 1 2 3\n", "bad.txt:2: the times must increase"},
    };
    for (const auto& [text, expect] : bad) {
        risknav::test::writeFile(dir + "/bad.txt", text);
        try {
            (void)readGroundTruth(dir + "/bad.txt");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const risknav::common::CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find(expect), std::string::npos)
                << e.what() << " for " << text;
        }
    }
}

namespace {
/** Every key `o` declares is in `section` of the documented config, with a
 * doc, and where the file gives the default, as the struct writes it. */
void expectDocumented(const risknav::common::CDeclaredOptions& o,
                      const std::string& section, size_t count) {
    mrpt::config::CConfigFileMemory doc(risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-afraid-learn.ini")));
    const auto keys = o.keys();
    ASSERT_EQ(keys.size(), count);
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists(section, k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        const std::string v = doc.read_string(section, k.key, "");
        EXPECT_EQ(v.substr(0, v.find_first_of(" \t/")), k.defaultText) << k.key;
    }
}
}  // namespace

TEST(TKrrOptions, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    // the kernel keys live in the host's section ([AfraidLearn] here)
    expectDocumented(TKrrOptions(), "AfraidLearn", 3);
}

TEST(CAfraidDetectorOptions, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    expectDocumented(CAfraidDetector::TOptions(), "AfraidDetector", 7);
}

TEST(CAfraidLearnerOptions, TheDocumentedConfigHoldsEveryDeclaredKey) {
    mrpt::config::CConfigFileMemory doc(risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-afraid-learn.ini")));
    const auto keys = CAfraidLearner::TOptions().keys();
    ASSERT_EQ(keys.size(), 25u);
    // the example's inputs and output name differ from the defaults (none)
    const std::set<std::string> example = {"map_file", "rawlogs", "afraid_name",
                                           "groundtruth_file"};
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists("AfraidLearn", k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        if (example.count(k.key))
            continue;
        const std::string v = doc.read_string("AfraidLearn", k.key, "");
        EXPECT_EQ(v.substr(0, v.find_first_of(" \t/")), k.defaultText) << k.key;
    }
}
