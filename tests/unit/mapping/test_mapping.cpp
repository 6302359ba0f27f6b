#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/mapping/CDistanceField.h>
#include <risknav/mapping/TSensorModel.h>
#include <risknav/mapping/scan_points.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>
#include "test_support.h"

#include <cmath>
#include <limits>
#include <random>

using namespace risknav::mapping;
using mrpt::maps::COccupancyGridMap2D;

namespace {
// A 3 x 2 m map, 10 cm cells, free except for the given cells.
COccupancyGridMap2D smallMap(const std::vector<std::pair<int, int>>& obstacles) {
    COccupancyGridMap2D g(-1.0, 2.0, 0.0, 2.0, 0.1f);
    g.fill(1.0f);
    for (const auto& [cx, cy] : obstacles)
        g.setCell(cx, cy, 0.0f);
    return g;
}
}  // namespace

TEST(ObstacleRule, ThresholdsAndUnknown) {
    TObstacleRule r;
    EXPECT_TRUE(r.isObstacle(0.0f));
    EXPECT_FALSE(r.isObstacle(1.0f));
    EXPECT_TRUE(r.isObstacle(0.5f));  // unknown, counted as obstacle
    r.unknown_is_obstacle = false;
    EXPECT_FALSE(r.isObstacle(0.5f));
    EXPECT_TRUE(r.isObstacle(0.3f));   // occupancy 0.7 >= 0.65
    EXPECT_FALSE(r.isObstacle(0.7f));  // occupancy 0.3 <= 0.35: free
}

TEST(ObstacleRule, ValidateRejectsCrossedThresholds) {
    TObstacleRule r;
    r.free_threshold = 0.7;
    try {
        r.validate();
        FAIL() << "no error";
    } catch (const risknav::common::CConfigKeyError& e) {
        EXPECT_NE(std::string(e.what()).find("[World] free_threshold"), std::string::npos)
            << e.what();
    }
    r.free_threshold = 0.35;
    r.occupied_threshold = 2;
    EXPECT_THROW(r.validate(), risknav::common::CConfigKeyError);
}

TEST(DistanceField, IndexingEqualsMrpt) {
    const auto g = smallMap({});
    CDistanceField f(g, TObstacleRule{});
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ux(g.getXMin(), g.getXMax() - 1e-9),
        uy(g.getYMin(), g.getYMax() - 1e-9);
    for (int i = 0; i < 2000; i++) {
        const double x = ux(rng), y = uy(rng);
        ASSERT_EQ(f.x2idx(x), g.x2idx(x)) << x;
        ASSERT_EQ(f.y2idx(y), g.y2idx(y)) << y;
    }
    EXPECT_EQ(f.x2idx(g.getXMin() - 0.01), -1);  // MRPT truncates to 0 here
}

TEST(DistanceField, ClearanceEqualsBruteForce) {
    std::mt19937 rng(5);
    std::vector<std::pair<int, int>> obst;
    for (int i = 0; i < 12; i++)
        obst.emplace_back(int(rng() % 30), int(rng() % 20));
    const auto g = smallMap(obst);
    for (bool outside : {true, false}) {
        TObstacleRule rule;
        rule.outside_is_obstacle = outside;
        CDistanceField f(g, rule);
        for (int cy = 0; cy < f.sizeY(); cy++)
            for (int cx = 0; cx < f.sizeX(); cx++) {
                double best = std::numeric_limits<double>::infinity();
                for (int oy = -1; oy <= f.sizeY(); oy++)
                    for (int ox = -1; ox <= f.sizeX(); ox++) {
                        const bool in = f.inside(ox, oy);
                        const bool o = in ? g.getCell(ox, oy) < 0.5f : outside;
                        if (o)
                            best = std::min(best, 0.1 * std::hypot(ox - cx, oy - cy));
                    }
                ASSERT_NEAR(f.clearance(cx, cy), best, 1e-3) << cx << " " << cy;
                ASSERT_EQ(f.isObstacle(cx, cy), g.getCell(cx, cy) < 0.5f);
            }
        EXPECT_EQ(f.isObstacle(-1, 0), outside);
        EXPECT_LE(f.obstacleCount(), obst.size());
    }
}

TEST(DistanceField, PointClearanceIsTheExactDistanceToTheCellSquares) {
    // the collision check: from a point (not its cell's centre) to the
    // obstacle cells' squares (not their centres), against brute force
    std::mt19937 rng(9);
    std::vector<std::pair<int, int>> obst;
    for (int i = 0; i < 12; i++)
        obst.emplace_back(int(rng() % 30), int(rng() % 20));
    const auto g = smallMap(obst);
    TObstacleRule rule;
    rule.outside_is_obstacle = true;
    const CDistanceField f(g, rule);
    std::uniform_real_distribution<double> ux(f.xMin(), f.xMax()), uy(f.yMin(), f.yMax());
    int near = 0;
    for (int k = 0; k < 2000; k++) {
        const double x = ux(rng), y = uy(rng);
        double best = std::numeric_limits<double>::infinity();
        for (int oy = -1; oy <= f.sizeY(); oy++)
            for (int ox = -1; ox <= f.sizeX(); ox++) {
                if (!f.isObstacle(ox, oy))
                    continue;
                const double r = f.resolution();
                const double x0 = f.xMin() + ox * r, y0 = f.yMin() + oy * r;
                best = std::min(best, std::hypot(std::max({x0 - x, 0.0, x - x0 - r}),
                                                 std::max({y0 - y, 0.0, y - y0 - r})));
            }
        const double reach = 0.35;
        const double c = f.pointClearance(x, y, reach);
        if (best <= reach) {
            ASSERT_NEAR(c, best, 1e-9) << x << " " << y;
            near++;
        } else {
            ASSERT_GT(c, reach - 1e-9) << x << " " << y;
        }
        // the cell-centre clearance can exceed the exact one by up to a cell
        EXPECT_LE(best, f.clearanceAt(x, y) + 1e-9);
    }
    EXPECT_GT(near, 200);
}

TEST(DistanceField, OpenMapIsBoundedByItsOutside) {
    const auto g = smallMap({});
    TObstacleRule rule;
    CDistanceField f(g, rule);
    // Centre cell (15, 10): the outside ring is 11 cells away (row -1 or 20).
    EXPECT_NEAR(f.clearance(15, 10), 1.0, 1e-6);
    EXPECT_EQ(f.clearanceAt(-5, 1), 0.0);
    rule.outside_is_obstacle = false;
    CDistanceField open(g, rule);
    EXPECT_TRUE(std::isinf(open.clearance(15, 10)));
}

// The nearest obstacle cell of every cell (a labelled 5x5 chamfer transform):
// an obstacle cell (a ring cell only when the outside is an obstacle), as near
// as the exact nearest within 4 % (the chamfer norm errs by up to 2 % either
// way), and its distance the chamfer's, within 2 % of Euclidean.
TEST(DistanceField, NearestObstaclesAgreeWithBruteForce) {
    std::mt19937 rng(9);
    std::vector<std::pair<int, int>> obst;
    for (int i = 0; i < 10; i++)
        obst.emplace_back(int(rng() % 30), int(rng() % 20));
    const auto g = smallMap(obst);
    for (bool outside : {true, false}) {
        TObstacleRule rule;
        rule.outside_is_obstacle = outside;
        const CDistanceField f(g, rule);
        const TNearestObstacles n = f.nearestObstacles();
        ASSERT_TRUE(n.any);
        ASSERT_EQ(n.obstX.size(), size_t(f.sizeX() * f.sizeY()));
        for (int cy = 0; cy < f.sizeY(); cy++)
            for (int cx = 0; cx < f.sizeX(); cx++) {
                const size_t i = n.index(cx, cy);
                const int ox = n.obstX[i], oy = n.obstY[i];
                ASSERT_TRUE(f.isObstacle(ox, oy)) << cx << " " << cy;
                ASSERT_TRUE(ox >= -1 && oy >= -1 && ox <= f.sizeX() && oy <= f.sizeY());
                const double named = std::hypot(ox - cx, oy - cy);
                const double exact = f.clearance(cx, cy) / f.resolution();
                ASSERT_LE(named, exact * 1.04 + 1e-3) << cx << " " << cy;
                ASSERT_NEAR(n.distCells[i], named, 0.02 * named + 1e-3);
                if (f.isObstacle(cx, cy)) {
                    ASSERT_EQ(ox, cx);
                    ASSERT_EQ(oy, cy);
                }
            }
    }
    // Nothing at all: no obstacle to name. Only the outside: the ring.
    TObstacleRule rule;
    rule.outside_is_obstacle = false;
    EXPECT_FALSE(CDistanceField(smallMap({}), rule).nearestObstacles().any);
    rule.outside_is_obstacle = true;
    const CDistanceField ring(smallMap({}), rule);
    const auto n = ring.nearestObstacles();
    ASSERT_TRUE(n.any);
    EXPECT_EQ(n.obstX[n.index(0, 10)], -1);
    EXPECT_EQ(n.obstY[n.index(15, 19)], 20);
    EXPECT_NEAR(n.distCells[n.index(0, 10)], 1.0, 1e-6);
}

TEST(ScanPoints, RightToLeftAndSensorPose) {
    mrpt::obs::CObservation2DRangeScan s;
    s.aperture = M_PI;
    s.resizeScan(3);
    for (size_t i = 0; i < 3; i++) {
        s.setScanRange(i, 2.0f);
        s.setScanRangeValidity(i, true);
    }
    s.setScanRangeValidity(1, false);
    s.sensorPose = mrpt::poses::CPose3D(0.5, 0.1, 0.3, 0, 0, 0);
    s.rightToLeft = true;
    auto p = scanToRobotFrame(s);
    ASSERT_EQ(p.size(), 2u);
    EXPECT_NEAR(p[0].x, 0.5, 1e-6);  // ray 0 points right (-90 deg)
    EXPECT_NEAR(p[0].y, 0.1 - 2.0, 1e-6);
    EXPECT_NEAR(p[1].y, 0.1 + 2.0, 1e-6);
    s.rightToLeft = false;
    p = scanToRobotFrame(s);
    EXPECT_NEAR(p[0].y, 0.1 + 2.0, 1e-6);  // mirrored: ray 0 points left
    s.sensorPose = mrpt::poses::CPose3D(0, 0, 0, M_PI / 2, 0, 0);
    s.rightToLeft = true;
    p = scanToRobotFrame(s);
    EXPECT_NEAR(p[0].x, 2.0, 1e-6);  // rotated by the sensor's yaw
    EXPECT_NEAR(p[0].y, 0.0, 1e-6);
}

TEST(DistanceField, DepthInsideObstacles) {
    // A wall 7 cells thick (columns 10..16) across the map.
    std::vector<std::pair<int, int>> wall;
    for (int cy = 0; cy < 20; cy++)
        for (int cx = 10; cx <= 16; cx++)
            wall.emplace_back(cx, cy);
    const auto g = smallMap(wall);
    const CDistanceField f(g, TObstacleRule{});
    EXPECT_EQ(f.depth(5, 5), 0.0);           // free
    EXPECT_NEAR(f.depth(10, 5), 0.1, 1e-6);  // the wall's face: next to free space
    EXPECT_NEAR(f.depth(13, 5), 0.4, 1e-6);  // its middle
    EXPECT_EQ(f.clearance(13, 5), 0.0);      // inside: no clearance
    EXPECT_EQ(f.depth(-1, 5), 0.0);          // off the map
}

TEST(SensorModel, TheExploreConfigDocumentsEveryDeclaredKey) {
    // config/risknav-explore.ini documents both sensor models key by key,
    // [MapRange2] with the struct's defaults (the stereo-like sensor's) but
    // its range_uncertainty_quad
    const mrpt::config::CConfigFileMemory doc(
        risknav::test::readFile(risknav::test::sourcePath("config/risknav-explore.ini")));
    const auto keys = TSensorModel().keys();
    ASSERT_EQ(keys.size(), 4u);
    for (const auto& k : keys) {
        EXPECT_FALSE(k.doc.empty()) << k.key;
        EXPECT_TRUE(doc.keyExists("MapLaser", k.key)) << k.key;
        ASSERT_TRUE(doc.keyExists("MapRange2", k.key)) << k.key;
        if (k.key == "range_uncertainty_quad")
            continue;
        std::string v = doc.read_string("MapRange2", k.key, "");
        v = v.substr(0, v.find_first_of(" \t/"));
        EXPECT_EQ(v, k.defaultText) << k.key;
    }
    // the rule across keys stays, after the ranges
    TSensorModel m;
    m.loadFromConfigFile(doc, "MapLaser");
    m.p_obs_given_free = 0.8;
    try {
        m.validate();
        FAIL() << "no error";
    } catch (const risknav::common::CConfigKeyError& e) {
        EXPECT_EQ(e.section, "MapLaser");
        EXPECT_EQ(e.key, "p_obs_given_obstacle");
    }
}
