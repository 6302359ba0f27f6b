// Route and sensing point names become file names (cov_<route>[+<points>].csv,
// ellipses_<route>.png): two names that give one file name, and names too
// long for the file system, are refused by validate().
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/risk/CRiskEvaluator.h>

#include <gtest/gtest.h>

using namespace risknav::risk;
using risknav::common::CConfigKeyError;

namespace {
CRiskEvaluator evaluator(const std::vector<std::string>& routes,
                         const std::vector<std::string>& points = {}, int gvg = 0) {
    CRiskEvaluator ev;
    ev.options.map.map_file = "map.png";
    ev.options.start = {0, 0};
    ev.options.goal = {10, 0};
    ev.options.gvg_routes = gvg;
    for (size_t i = 0; i < routes.size(); i++) {
        TRouteOptions r;
        r.section = "Route" + std::to_string(i + 1);
        r.name = routes[i];
        r.waypoints = {0, 0, 10, 0};
        ev.configRoutes.push_back(r);
    }
    for (size_t i = 0; i < points.size(); i++) {
        TSensingPointOptions p;
        p.section = "SensingPoint" + std::to_string(i + 1);
        p.name = points[i];
        p.x = 5;
        p.y = 0;
        ev.sensingPoints.push_back(p);
    }
    return ev;
}

std::string errorOf(const CRiskEvaluator& ev) {
    try {
        ev.validate();
    } catch (const CConfigKeyError& e) {
        return e.what();
    }
    return "(no error)";
}
}  // namespace

TEST(RiskOutputNames, NamesThatGiveOneFileNameAreRefusedNamingBoth) {
    // 'a b' and 'a_b' both wrote cov_a_b.csv: the second overwrote the first
    EXPECT_EQ(errorOf(evaluator({"a b", "a_b"})),
              "[Route2] name = 'a_b': its files cov_a_b.csv and ellipses_a_b.png would "
              "be those of [Route1] name = 'a b' (file names keep letters, digits, '-' "
              "and '_'); rename one");
    // two non-ASCII names of the same length
    EXPECT_NE(errorOf(evaluator({"\xC3\xA9t\xC3\xA9", "\xC3\xBCt\xC3\xBC"}))
                  .find("[Route2] name"),
              std::string::npos);
    // a GVG route's name, and the best row's image
    EXPECT_NE(errorOf(evaluator({"G2"}, {}, 3)).find("would be those of GVG route G2"),
              std::string::npos);
    EXPECT_EQ(errorOf(evaluator({"G2"}, {}, 1)), "(no error)");
    EXPECT_NE(errorOf(evaluator({"best"})).find("the best row (ellipses_best.png)"),
              std::string::npos);
    // a route 'A+SP1' and route A with sensing point SP1: '+' is no longer kept
    EXPECT_EQ(CRiskEvaluator::covFileName("A+SP1", {}), "cov_A_SP1.csv");
    EXPECT_EQ(CRiskEvaluator::covFileName("A", {"SP1"}), "cov_A+SP1.csv");
    // sensing points: 'SP 1' and 'SP_1' would write the same cov_<route>+SP_1.csv
    EXPECT_NE(errorOf(evaluator({"A"}, {"SP 1", "SP_1"}))
                  .find("[SensingPoint2] name = 'SP_1': in file names"),
              std::string::npos);
    EXPECT_EQ(errorOf(evaluator({"a b", "a-b", "A_B"}, {"SP1", "SP2"}, 2)), "(no error)");
}

TEST(RiskOutputNames, NamesTooLongForAFileNameAreRefused) {
    const std::string longName(300, 'r');
    const std::string e = errorOf(evaluator({longName}));
    EXPECT_EQ(e.rfind("[Route1] name = '" + std::string(60, 'r') +
                          "... (300 bytes)': makes "
                          "the output file name 'cov_",
                      0),
              0u)
        << e;
    EXPECT_NE(e.find("' 308 bytes long; at most 235"), std::string::npos) << e;
    // each name fits, but a row visiting two sensing points would not
    const std::string e2 =
        errorOf(evaluator({"A"}, {std::string(120, 'p'), std::string(120, 'q')}));
    EXPECT_EQ(e2.rfind("[SensingPoint1] name = '", 0), 0u) << e2;
    EXPECT_NE(e2.find("bytes long; at most 235"), std::string::npos) << e2;
    // the same with one sensing point a row: fine
    auto ev = evaluator({"A"}, {std::string(120, 'p'), std::string(120, 'q')});
    ev.options.max_sensing_subset = 1;
    EXPECT_EQ(errorOf(ev), "(no error)");
    // the longest name that fits: cov_<name>.csv and ellipses_<name>.png
    EXPECT_EQ(errorOf(evaluator({std::string(235 - 13, 'r')})), "(no error)");
    EXPECT_NE(errorOf(evaluator({std::string(235 - 12, 'r')})), "(no error)");
}
