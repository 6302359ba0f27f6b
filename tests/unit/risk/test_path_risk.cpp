#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/geometry/polyline.h>
#include <risknav/risk/CRiskEvaluator.h>
#include <risknav/risk/path_risk.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <set>

using namespace risknav::risk;
using mrpt::math::TPoint2D;
using risknav::geometry::polylineLength;

namespace {
// A straight corridor 2 m wide (walls at y = 0 and y = 2), 30 m long.
mrpt::maps::COccupancyGridMap2D corridor() {
    mrpt::maps::COccupancyGridMap2D g(0, 30, -0.5, 2.5, 0.05f);
    g.fill(1.0f);
    for (unsigned cx = 0; cx < g.getSizeX(); cx++)
        for (unsigned cy = 0; cy < g.getSizeY(); cy++) {
            const double y = g.idx2y(cy);
            if (y < 0 || y > 2)
                g.setCell(cx, cy, 0.0f);
        }
    return g;
}

TRiskOptions paperOptions() {
    TRiskOptions o;  // the paper's robot (001 sections 4.4, 6.2)
    o.sigmaP0.diagonal() << 1e-6, 1e-6, 0.01;  // (1 mm, 1 mm, 0.1 rad)^2
    return o;
}
}  // namespace

TEST(PathRisk, TrapezoidIntegral) {
    EXPECT_DOUBLE_EQ(integrateRisk({0, 1, 3}, {1, 3, 3}), 2.0 + 6.0);
    EXPECT_DOUBLE_EQ(riskDensity(2.0), 0.25);
    EXPECT_TRUE(std::isinf(riskDensity(0.0)));
}

TEST(PathRisk, UGrowsAlongACorridorAndDropsAtASensingPoint) {
    const CObstacleField f(corridor(), {}, 0.25);
    const std::vector<TPoint2D> path = {{1, 1}, {29, 1}};
    for (TErrorModel model : {TErrorModel::PerStep, TErrorModel::Systematic}) {
        TRiskOptions o = paperOptions();
        o.model = model;
        const auto r = evaluatePathRisk(path, {}, f, o);
        ASSERT_GT(r.samples.size(), 500u);
        EXPECT_NEAR(r.length, 28.0, 1e-9);
        for (size_t i = 1; i < r.samples.size(); i++)
            ASSERT_GE(r.samples[i].u, r.samples[i - 1].u * (1 - 1e-12))
                << "s = " << r.samples[i].s;
        EXPECT_GT(r.samples.back().u, r.samples.front().u);

        // With a sensing point at x = 15: u right after it equals u of a robot
        // starting there with the reset covariance, then grows again.
        TSensingPoint sp;
        sp.name = "SP";
        sp.x = 15;
        sp.y = 1;
        sp.radius = 0.1;
        sp.resetCov = o.sigmaP0;
        const auto rs = evaluatePathRisk(path, {sp}, f, o);
        ASSERT_EQ(rs.sensed, std::vector<std::string>{"SP"});
        const auto it = std::find_if(rs.samples.begin(), rs.samples.end(),
                                     [](const TRiskSample& k) { return k.sensedHere; });
        ASSERT_NE(it, rs.samples.end());
        const auto fresh = evaluatePathRisk({{it->x, 1}, {29, 1}}, {}, f, o);
        EXPECT_NEAR(it->u / fresh.samples.front().u, 1.0, 0.05) << "model " << int(model);
        EXPECT_LT(it->u, (it - 1)->u / 2);
        EXPECT_LT(rs.U, r.U);
        EXPECT_GT(rs.samples.back().u, it->u);
    }
}

TEST(PathRisk, NarrowerMeansRiskier) {
    const CObstacleField f(corridor(), {}, 0.25);
    const auto centre = evaluatePathRisk({{1, 1}, {20, 1}}, {}, f, paperOptions());
    const auto offCentre = evaluatePathRisk({{1, 0.6}, {20, 0.6}}, {}, f, paperOptions());
    EXPECT_GT(offCentre.U, centre.U);
    EXPECT_GT(offCentre.uMax, centre.uMax);
    EXPECT_FALSE(centre.blocked);
    // Through the wall: D_max = 0 somewhere, u infinite: blocked.
    EXPECT_TRUE(
        evaluatePathRisk({{1, 1}, {5, 1}, {5, 3}}, {}, f, paperOptions()).blocked);
}

TEST(PathRisk, SensingDetours) {
    const CObstacleField f(corridor(), {}, 0.25);
    const std::vector<TPoint2D> route = {{1, 1}, {29, 1}};
    TSensingPoint a, b;
    a.name = "A";
    a.x = 20;
    a.y = 1.5;  // off the route by 0.5 m: a detour
    b.name = "B";
    b.x = 10;
    b.y = 1.05;  // within its radius of the route: no detour
    std::vector<TPoint2D> out;
    ASSERT_TRUE(routeWithSensingDetours(route, {a, b}, f, out));
    ASSERT_EQ(out.size(), 5u);  // start, P, A, P, end
    EXPECT_NEAR(out[1].x, 20, 1e-9);
    EXPECT_NEAR(out[2].y, 1.5, 1e-9);
    EXPECT_NEAR(polylineLength(out), 28 + 1.0, 1e-9);
    // Behind a wall: no detour possible.
    TSensingPoint c;
    c.x = 10;
    c.y = 2.3;
    EXPECT_FALSE(routeWithSensingDetours(route, {c}, f, out));
}

// Options set from code run the same validate() as options read from a file;
// saveToConfigFile() writes what loadFromConfigFile() reads back exactly.
TEST(RiskOptions, SetFromCodeAreValidatedAndRoundTrip) {
    using risknav::common::CConfigKeyError;
    CRiskEvaluator ev;  // no map, no start, no goal
    EXPECT_THROW(ev.evaluate(), CConfigKeyError);
    TPropagationOptions p;
    p.speed = 0;
    EXPECT_THROW(p.validate(), CConfigKeyError);
    TSensingPointOptions sp;  // x, y required
    sp.name = "S";
    EXPECT_THROW(sp.validate(), CConfigKeyError);

    CRiskEvaluator::TOptions o;
    o.map.map_file = risknav::test::sourcePath("datasets/risk-two-routes/two_routes.png");
    o.start = {2.0, 7.0};
    o.goal = {22.0, 7.0};
    o.obstacles.outside_is_obstacle = false;
    o.eval_step = 0.1 / 3;
    o.gvg.separation_ratio = 0.7;
    EXPECT_NO_THROW(o.validate());
    mrpt::config::CConfigFileMemory m;
    o.saveToConfigFile(m, "RiskEval");
    CRiskEvaluator::TOptions r;
    r.loadFromConfigFile(m, "RiskEval");
    mrpt::config::CConfigFileMemory m2;
    r.saveToConfigFile(m2, "RiskEval");
    EXPECT_EQ(m.getContent(), m2.getContent());
    EXPECT_EQ(r.eval_step, o.eval_step);
    EXPECT_FALSE(r.obstacles.outside_is_obstacle);
    EXPECT_EQ(r.gvg.separation_ratio, 0.7);
}

// error_model none: exact wheels, only the initial error and the noise count.
TEST(RiskOptions, ErrorModelNoneMeansExactWheels) {
    risknav::common::TOdometryOptions odo;
    odo.error_model = "none";
    const TRiskOptions o = makeRiskOptions(odo, TPropagationOptions{}, 0.05);
    EXPECT_EQ(o.odometry.sigmaM(), Eigen::Matrix3d::Zero());
    EXPECT_EQ(o.odometry.radiusL, odo.wheel_radius_l);
    EXPECT_NEAR(o.sigmaP0(2, 2), 0.01, 1e-15);  // (0.1 rad)^2
    odo.error_model = "systematic";
    EXPECT_EQ(makeRiskOptions(odo, {}, 0.05).model, TErrorModel::Systematic);
    EXPECT_NEAR(makeRiskOptions(odo, {}, 0.05).odometry.sigmaT, 0.001, 1e-15);
}

// Sigmas near 1e154 overflowed the covariance to inf, D_max read inf
// and U = 0: a hopeless route scored perfectly safe. The config bounds the
// sigmas now (validate()); whatever still overflows is reported, never read
// as safety: the evaluation stops with `failure`, U and u_max are +inf; D_max
// of a covariance that is not finite is NaN, not inf.
TEST(PathRisk, AnOverflowIsReportedNeverReadAsSafety) {
    const CObstacleField f(corridor(), {}, 0.25);
    const std::vector<TPoint2D> path = {{1, 1}, {29, 1}};
    for (TPropagation p : {TPropagation::Linear, TPropagation::Cubature5}) {
        TRiskOptions o = paperOptions();
        o.propagation = p;
        for (double big : {1e307, 1e308}) {  // u overflows; the covariance too
            o.sigmaP0.diagonal() << big, big, 1;
            const auto r = evaluatePathRisk(path, {}, f, o);
            EXPECT_NE(r.failure.find("overflow"), std::string::npos) << int(p);
            EXPECT_TRUE(std::isinf(r.U) && r.U > 0);
            EXPECT_GT(r.uMax, 1e300);
            EXPECT_FALSE(r.blocked);  // not a collision
        }
        // A sensing point whose reset covariance overflows does not "help".
        o.sigmaP0 = paperOptions().sigmaP0;
        TSensingPoint sp;
        sp.name = "SP";
        sp.x = 15;
        sp.y = 1;
        sp.resetCov.diagonal() << 1e308, 1e308, 1e308;
        const auto rs = evaluatePathRisk(path, {sp}, f, o);
        EXPECT_FALSE(rs.failure.empty());
        EXPECT_TRUE(std::isinf(rs.U));
    }
    Eigen::Matrix2d inf = Eigen::Matrix2d::Identity();
    inf(0, 0) = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(std::isnan(f.dMax(10, 1, inf).d));
    // Huge but finite: a tiny D_max (very risky), never NaN.
    const double d = f.dMax(10, 1, Eigen::Matrix2d::Identity() * 1e300).d;
    EXPECT_TRUE(std::isfinite(d));
    EXPECT_LT(d, 1e-100);
}

// The evaluator turns such a row into an excluded one with the reason (set
// from code past validate(), which would refuse these sigmas).
TEST(RiskOptions, TheSigmasAreBoundedAndAnOverflowExcludesTheRow) {
    using risknav::common::CConfigKeyError;
    TPropagationOptions p;
    p.init_sigma_x = 1e154;
    EXPECT_THROW(p.validate(), CConfigKeyError);
    p = {};
    p.noise_sigma_x = 11;
    EXPECT_THROW(p.validate(), CConfigKeyError);
    p = {};
    p.propagation = "ukf";
    EXPECT_THROW(p.validate(), CConfigKeyError);
    TSensingPointOptions sp;
    sp.name = "S";
    sp.x = sp.y = 1;
    sp.sigma_y = 1e308;
    EXPECT_THROW(sp.validate(), CConfigKeyError);

    CRiskEvaluator ev;
    ev.options.map.map_file =
        risknav::test::sourcePath("datasets/risk-two-routes/two_routes.png");
    ev.options.start = {2.0, 7.0};
    ev.options.goal = {22.0, 7.0};
    ev.options.gvg_routes = 1;
    ev.prepare();
    ev.propagation.init_sigma_x = ev.propagation.init_sigma_y = 1e200;
    ev.evaluate();
    ASSERT_FALSE(ev.rows().empty());
    for (const auto& r : ev.rows()) {
        EXPECT_TRUE(r.excluded);
        EXPECT_NE(r.reason.find("overflow"), std::string::npos);
        EXPECT_TRUE(std::isinf(r.result.U));
    }
    EXPECT_EQ(ev.best(), -1);
}

namespace {
// Each declared key of `o` is documented in `section` of
// config/risknav-risk-eval.ini with a doc of its own, and where the file
// gives the default, it writes the same text (but for the keys in `rounded`).
void expectDocumented(const risknav::common::CDeclaredOptions& o,
                      const std::string& section, size_t count,
                      const std::set<std::string>& rounded = {}) {
    mrpt::config::CConfigFileMemory doc(risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-risk-eval.ini")));
    const auto keys = o.keys();
    ASSERT_EQ(keys.size(), count);
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists(section, k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        const std::string v = doc.read_string(section, k.key, "");
        if (!rounded.count(k.key)) {
            EXPECT_EQ(risknav::common::trim(v.substr(0, v.find("//"))), k.defaultText)
                << k.key;
        }
    }
}
}  // namespace

TEST(RiskOptions, TheDocumentedConfigHoldsEveryDeclaredKey) {
    // the file writes 5.73 for 0.1 rad
    expectDocumented(TPropagationOptions(), "Odometry", 11, {"init_sigma_theta_deg"});
    expectDocumented(CGvgRoutes::TOptions(), "RiskEval", 2);
    // [RiskEval] is read back from memory: gvg's keys are found there
    CRiskEvaluator::TOptions o;
    o.gvg.simplify_tolerance = 0.25;
    mrpt::config::CConfigFileMemory m;
    o.saveToConfigFile(m, "RiskEval");
    EXPECT_EQ(m.read_string("RiskEval", "gvg_simplify_tolerance", ""), "0.25");
    // [RiskEval] with the map's, the obstacle rule's and gvg's keys; the file
    // gives a map, the start and goal (no defaults) and its own interval
    expectDocumented(CRiskEvaluator::TOptions(), "RiskEval", 20,
                     {"map_file", "start", "goal", "ellipse_interval"});
    // a route's and a sensing point's own values (no defaults: names, points)
    expectDocumented(TRouteOptions(), "Route1", 2, {"name", "waypoints"});
    expectDocumented(TSensingPointOptions(), "SensingPoint1", 7,
                     {"name", "x", "y", "sigma_theta_deg"});
}

// A route's and a sensing point's name is its section's unless given; the
// points are required.
TEST(RiskOptions, NamesDefaultToTheSectionAndPointsAreRequired) {
    mrpt::config::CConfigFileMemory c(
        "[Route7]\nwaypoints = 1 2 3 4\n[SensingPoint3]\nx = 1\ny = 2\n"
        "[SensingPoint4]\nx = 1\n");
    TRouteOptions r;
    r.loadFromConfigFile(c, "Route7");
    EXPECT_EQ(r.name, "Route7");
    EXPECT_EQ(r.waypoints.size(), 4u);
    TSensingPointOptions p;
    p.loadFromConfigFile(c, "SensingPoint3");
    EXPECT_EQ(p.name, "SensingPoint3");
    EXPECT_NO_THROW(p.validate());
    try {
        TSensingPointOptions q;
        q.loadFromConfigFile(c, "SensingPoint4");
        ADD_FAILURE() << "y is required";
    } catch (const std::exception& e) {
        EXPECT_NE(
            std::string(e.what()).find("[SensingPoint4] y: required key is missing"),
            std::string::npos)
            << e.what();
    }
    TRouteOptions none;
    none.loadFromConfigFile(c, "SensingPoint3");  // no waypoints key
    try {
        none.validate();
        ADD_FAILURE() << "waypoints are required";
    } catch (const risknav::common::CConfigKeyError& e) {
        EXPECT_NE(std::string(e.what()).find("[SensingPoint3] waypoints = '': required"),
                  std::string::npos)
            << e.what();
    }
}
