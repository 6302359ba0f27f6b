// End-to-end: risknav-viewpoint-plan on datasets/landmarks-*, the comparison
// of robots R1 and R2 of Yamashita et al. (004 section V, Tables II/III) and
// the maps beyond the paper's; bad input.
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/nav/reactive/TWaypoint.h>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "test_support.h"

using namespace risknav::test;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
json planRun(const std::string& ini, const std::string& out,
             const std::string& extra = "") {
    const auto r = run(binPath("risknav-viewpoint-plan") + " -q -o '" + out + "' " +
                       extra + " '" + ini + "'");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readJson(out + "/summary.json");
}

std::string twoRoutes(const std::string& robot) {
    return sourcePath("datasets/landmarks-two-routes/" + robot + ".ini");
}

// Rows of a CSV file as maps column -> value.
std::vector<std::map<std::string, std::string>> csvRows(const std::string& path) {
    const auto lines = readLines(path);
    std::vector<std::map<std::string, std::string>> rows;
    auto split = [](const std::string& l) {
        std::vector<std::string> c;
        std::stringstream ss(l);
        for (std::string t; std::getline(ss, t, ',');)
            c.push_back(t);
        return c;
    };
    const auto head = split(lines.at(0));
    for (size_t i = 1; i < lines.size(); i++) {
        if (lines[i].empty())
            continue;
        const auto c = split(lines[i]);
        std::map<std::string, std::string> m;
        for (size_t k = 0; k < head.size() && k < c.size(); k++)
            m[head[k]] = c[k];
        rows.push_back(m);
    }
    return rows;
}
}  // namespace

TEST(ViewpointPlanE2E, R1TakesTheShortRouteR2TheLongOne) {
    const json r1 = planRun(twoRoutes("r1"), freshDir("r1"));
    const json r2 = planRun(twoRoutes("r2"), freshDir("r2"));
    ASSERT_EQ(r1["status"], "ok");
    ASSERT_EQ(r2["status"], "ok");
    // Route 1 is the homotopy class of the shortest path (the lower corridor).
    EXPECT_EQ(r1["optimal"]["route"], 1);
    EXPECT_NE(r2["optimal"]["route"], 1);
    EXPECT_GT(r2["optimal"]["length_m"].get<double>(),
              r1["optimal"]["length_m"].get<double>() + 1.0);
    // R1 needs few viewpoints on it, fewer than R2 on the long route.
    EXPECT_LE(r1["optimal"]["viewpoints"].get<int>(), 6);
    EXPECT_LT(r1["optimal"]["viewpoints"].get<int>(),
              r2["optimal"]["viewpoints"].get<int>());
    // R2 cannot take the short route at any S; R1 can from some S on, with
    // fewer viewpoints as S grows (004 Table II's pattern).
    int r1ShortFeasible = 0, prev = 1 << 30;
    for (const auto& sp : r2["sweep"])
        for (const auto& p : sp["paths"])
            if (p["route"] == 1) {
                EXPECT_FALSE(p["feasible"].get<bool>()) << "R2, S " << sp["S"];
            }
    for (const auto& sp : r1["sweep"])
        for (const auto& p : sp["paths"])
            if (p["route"] == 1 && p["feasible"].get<bool>()) {
                r1ShortFeasible++;
                EXPECT_LE(p["viewpoints"].get<int>(), prev) << "S " << sp["S"];
                prev = p["viewpoints"];
            }
    EXPECT_GE(r1ShortFeasible, 4);
    // Small S is infeasible for both: the path hugs the obstacles, and the
    // allowed error there is S.
    for (const json* s : {&r1, &r2})
        for (const auto& p : (*s)["sweep"][0]["paths"])
            EXPECT_FALSE(p["feasible"].get<bool>());
    // Every path keeps the allowed error >= S (C-obstacles grown by R + S).
    for (const json* s : {&r1, &r2})
        for (const auto& sp : (*s)["sweep"])
            for (const auto& p : sp["paths"])
                EXPECT_GE(p["min_allowed_error_m"].get<double>(),
                          sp["S"].get<double>() - 1e-9);
    // The worst-case errors bound a Monte Carlo of the image errors.
    for (const json* s : {&r1, &r2}) {
        EXPECT_GT((*s)["monte_carlo"]["draws"].get<int>(), 1000);
        EXPECT_EQ((*s)["monte_carlo"]["failures"], 0);
        EXPECT_LE((*s)["monte_carlo"]["max_ratio_position"].get<double>(), 1.0);
        EXPECT_LE((*s)["monte_carlo"]["max_ratio_total"].get<double>(), 1.0);
        EXPECT_GT((*s)["monte_carlo"]["max_ratio_total"].get<double>(), 0.5);  // tight
    }
}

TEST(ViewpointPlanE2E, StrategiesFollowTheRuleAndThreeLandmarksAreUsed) {
    // At every viewpoint the chosen observation is the one that lets the
    // robot go furthest (eq. (1) at the distance it then travels); on the
    // landmark-rich upper route the three-landmark observation is chosen
    // where its geometry is good, and its error is then the smallest.
    const std::string out = freshDir("r2");
    const json s = planRun(twoRoutes("r2"), out);
    std::map<std::string, std::vector<std::map<std::string, std::string>>> byVp;
    for (const auto& r : csvRows(out + "/strategies.csv"))
        byVp[r.at("viewpoint")].push_back(r);
    ASSERT_EQ(byVp.size(), s["optimal"]["viewpoints"].get<size_t>());
    int cChosen = 0, cAvailable = 0;
    for (const auto& [vp, alts] : byVp) {
        const std::map<std::string, std::string>* chosen = nullptr;
        for (const auto& a : alts)
            if (a.at("chosen") == "true")
                chosen = &a;
        ASSERT_TRUE(chosen) << "viewpoint " << vp;
        for (const auto& a : alts)
            EXPECT_GE(std::stod(chosen->at("reach_m")),
                      std::stod(a.at("reach_m")) - 1e-12);
        bool hasC = false;
        for (const auto& a : alts)
            hasC = hasC || a.at("strategy") == "C";
        cAvailable += hasC;
        if (chosen->at("strategy") == "C") {
            cChosen++;
            for (const auto& a : alts)
                EXPECT_LE(std::stod(chosen->at("e_max_m")),
                          std::stod(a.at("e_max_m")) + 1e-12);
        }
    }
    EXPECT_GE(cAvailable, 3);
    EXPECT_GE(cChosen, 1);
    // The counts in summary.json are the CSV's.
    EXPECT_EQ(s["optimal"]["strategies"]["C"].get<int>(), cChosen);
}

TEST(ViewpointPlanE2E, OutputsAreCompleteAndMrptReadsTheWaypoints) {
    const std::string out = freshDir("r1");
    const json s = planRun(twoRoutes("r1"), out);
    for (const char* f : {"plan.png", "sweep.csv", "sweep.md", "strategies.csv",
                          "waypoints.ini", "summary.json", "config_effective.ini"})
        EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
    const cv::Mat img = cv::imread(out + "/plan.png");
    ASSERT_FALSE(img.empty());
    EXPECT_GT(img.cols, 600);
    // sweep.csv: one row per (S, path).
    size_t paths = 0;
    for (const auto& sp : s["sweep"])
        paths += sp["paths"].size();
    EXPECT_EQ(csvRows(out + "/sweep.csv").size(), paths);
    EXPECT_NE(readFile(out + "/sweep.md").find("(optimal)"), std::string::npos);
    // MRPT's own TWaypointSequence reads the plan; the viewpoints are the
    // waypoints that may not be skipped, in the [Viewpoints] section.
    mrpt::config::CConfigFileMemory ini(readFile(out + "/waypoints.ini"));
    mrpt::nav::TWaypointSequence seq;
    seq.load(ini, "Waypoints");
    ASSERT_EQ(seq.waypoints.size(), s["optimal"]["waypoints"].size());
    size_t fixed = 0;
    for (const auto& w : seq.waypoints)
        fixed += !w.allow_skip;
    EXPECT_EQ(fixed, s["optimal"]["viewpoints"].get<size_t>());
    std::vector<std::string> keys;
    ini.getAllKeys("Viewpoints", keys);
    EXPECT_EQ(keys.size(), fixed);
    // Every digit: the waypoints are the plan's (MRPT's own save rounds).
    for (size_t i = 0; i < seq.waypoints.size(); i++) {
        EXPECT_DOUBLE_EQ(seq.waypoints[i].target.x,
                         s["optimal"]["waypoints"][i][0].get<double>());
        EXPECT_DOUBLE_EQ(seq.waypoints[i].target.y,
                         s["optimal"]["waypoints"][i][1].get<double>());
    }
    EXPECT_NEAR(seq.waypoints.front().target.x, 0.45, 1e-9);
    EXPECT_NEAR(seq.waypoints.back().target.x, 3.95, 1e-9);
}

TEST(ViewpointPlanE2E, EffectiveConfigAndSeedReproduceTheRun) {
    const std::string a = freshDir("a"), b = freshDir("b");
    planRun(twoRoutes("r2"), a, "--seed 7");
    planRun(a + "/config_effective.ini", b);
    EXPECT_EQ(readFile(a + "/sweep.csv"), readFile(b + "/sweep.csv"));
    EXPECT_EQ(readFile(a + "/strategies.csv"), readFile(b + "/strategies.csv"));
    const json ja = readJson(a + "/summary.json"), jb = readJson(b + "/summary.json");
    EXPECT_EQ(ja["monte_carlo"], jb["monte_carlo"]);
    EXPECT_EQ(jb["seed"], 7);
    // One thread or two: the same plans.
    const std::string c = freshDir("c");
    planRun(twoRoutes("r2"), c, "--seed 7 --set ViewpointPlan.threads=1");
    EXPECT_EQ(readFile(a + "/sweep.csv"), readFile(c + "/sweep.csv"));
}

TEST(ViewpointPlanE2E, TheDocumentedConfigRunsAndListsEveryKey) {
    // config/risknav-viewpoint-plan.ini runs as it is (R1 on two-routes), and
    // every key the app writes to config_effective.ini is documented there.
    const std::string d = freshDir("cfg");
    const json s = planRun(sourcePath("config/risknav-viewpoint-plan.ini"), d);
    EXPECT_EQ(s["status"], "ok");
    const auto documented = iniKeys(sourcePath("config/risknav-viewpoint-plan.ini"));
    const auto written = iniKeys(d + "/config_effective.ini");
    EXPECT_GT(written.size(), 30u);
    for (const auto& k : written)
        EXPECT_TRUE(documented.count(k))
            << k << " is not in config/risknav-viewpoint-plan.ini";
}

TEST(ViewpointPlanE2E, MapsBeyondThePaper) {
    // A room with pillars and a long corridor with sparse landmarks, both
    // robots: feasible plans exist, keep the margin, and their bounds hold
    // against the Monte Carlo; R2 never needs fewer viewpoints than R1.
    for (const char* map : {"landmarks-pillars", "landmarks-corridor"}) {
        json s[2];
        for (int r = 0; r < 2; r++) {
            s[r] = planRun(sourcePath(std::string("datasets/") + map + "/r" +
                                      std::to_string(r + 1) + ".ini"),
                           freshDir("m"));
            ASSERT_EQ(s[r]["status"], "ok") << map;
            EXPECT_LE(s[r]["monte_carlo"]["max_ratio_total"].get<double>(), 1.0) << map;
            EXPECT_EQ(s[r]["monte_carlo"]["failures"], 0) << map;
            for (const auto& sp : s[r]["sweep"])
                for (const auto& p : sp["paths"])
                    EXPECT_GE(p["min_allowed_error_m"].get<double>(),
                              sp["S"].get<double>() - 1e-9);
        }
        EXPECT_GE(s[1]["optimal"]["viewpoints"].get<int>(),
                  s[0]["optimal"]["viewpoints"].get<int>())
            << map;
    }
}

TEST(ViewpointPlanE2E, NoLandmarkVisibleIsReportedNotAnError) {
    const std::string w = freshDir("w");
    writeFile(w + "/world.txt", "bounds 0 0 6 3\nobstacle 2 0 3 0 3 1 2 1\n");
    writeFile(w + "/p.ini",
              "[ViewpointPlan]\nworld_file = world.txt\nstart = 0.5 1.5\n"
              "goal = 5.5 1.5\n[Robot]\nradius = 0.3\n");
    const std::string out = freshDir("out");
    const json s = planRun(w + "/p.ini", out);
    EXPECT_EQ(s["status"], "no feasible plan");
    EXPECT_TRUE(s["optimal"].is_null());
    EXPECT_TRUE(fs::exists(out + "/plan.png"));
    for (const auto& sp : s["sweep"]) {
        ASSERT_FALSE(sp["paths"].empty());
        for (const auto& p : sp["paths"])
            EXPECT_FALSE(p["feasible"].get<bool>());
    }
}

TEST(ViewpointPlanE2E, StartNearAnObstacleIsInfeasibleForLargeMarginsOnly) {
    // The start 0.35 m from a wall, R = 0.3: free for S < 0.05, reported as
    // "start within R + S" for the larger margins; exit 0.
    const std::string w = freshDir("w");
    fs::copy_file(sourcePath("datasets/landmarks-two-routes/world.txt"),
                  w + "/world.txt");
    std::string ini = readFile(twoRoutes("r1"));
    ini = std::regex_replace(ini, std::regex("start = 0.45 0.6"), "start = 0.45 0.35");
    writeFile(w + "/p.ini", ini);
    const json s = planRun(w + "/p.ini", freshDir("out"));
    int blocked = 0;
    for (const auto& sp : s["sweep"]) {
        const bool tooNear = sp["S"].get<double>() > 0.05 + 1e-9;
        EXPECT_EQ(sp["start_free"].get<bool>(), !tooNear) << sp["S"];
        if (tooNear) {
            EXPECT_EQ(sp["note"], "start within R + S of an obstacle");
            EXPECT_TRUE(sp["paths"].empty());
            blocked++;
        }
    }
    EXPECT_GE(blocked, 3);
}

TEST(ViewpointPlanE2E, CollinearLandmarksOnAWallGiveNoNaN) {
    // Three (and more) landmarks in a row on one straight wall: the
    // three-landmark geometry is fine off the wall's line and no number in
    // the outputs is NaN or infinite.
    const std::string w = freshDir("w");
    writeFile(
        w + "/world.txt",
        "bounds 0 0 8 2\nlandmark A 2 2 -90\nlandmark B 2.2 2 -90\nlandmark C 2.4 2 -90\n"
        "landmark D 4 2 -90\nlandmark E 4.2 2 -90\nlandmark F 6 2 -90\n"
        "landmark G 6.2 2 -90\nlandmark H 6.4 2 -90\n");
    writeFile(w + "/p.ini",
              "[ViewpointPlan]\nworld_file = world.txt\nstart = 0.5 0.8\n"
              "goal = 7.5 0.8\nsafety_margins = 0.05 0.1\n[Robot]\nradius = 0.3\n");
    const std::string out = freshDir("out");
    const json s = planRun(w + "/p.ini", out);
    for (const char* f : {"sweep.csv", "strategies.csv"})
        for (const auto& row : csvRows(out + "/" + f))
            for (const auto& [col, v] : row)
                EXPECT_TRUE(v != "nan" && v != "inf" && v != "-inf") << f << " " << col;
    ASSERT_EQ(s["status"], "ok");
    for (const auto& v : s["optimal"]["viewpoint_list"]) {
        EXPECT_TRUE(v["e_pos_m"].is_number());  // a non-finite value would be null
        EXPECT_TRUE(v["e_max_m"].is_number());
    }
    EXPECT_GE(s["optimal"]["strategies"]["C"].get<int>(), 1);
}

TEST(ViewpointPlanE2E, GridMapIsTracedIntoPolygons) {
    // A 5 x 3 m room as a bitmap (10 cm walls all round, a 1 x 1 m block):
    // the walls become one obstacle with a hole (the room), the block another;
    // landmarks given on the walls' faces are moved onto the traced contour.
    const std::string w = freshDir("w");
    cv::Mat img(60, 100, CV_8UC1, cv::Scalar(255));
    cv::rectangle(img, cv::Rect(0, 0, 100, 60), cv::Scalar(0), 2);  // 2 px = 10 cm
    cv::rectangle(img, cv::Rect(40, 20, 20, 20), cv::Scalar(0), cv::FILLED);
    ASSERT_TRUE(cv::imwrite(w + "/room.png", img));
    writeFile(
        w + "/landmarks.txt",
        "landmark Bw 2.0 1.5 180\nlandmark Be 3.0 1.5 0\nlandmark Bs 2.5 1.0 -90\n"
        "landmark Bn 2.5 2.0 90\nlandmark W1 0.1 1.3 0\nlandmark W2 0.1 1.6 0\n"
        "landmark E1 4.9 1.3 180\nlandmark E2 4.9 1.6 180\nlandmark S1 1.2 0.1 90\n"
        "landmark S2 3.8 0.1 90\nlandmark N1 1.2 2.9 -90\nlandmark N2 3.8 2.9 -90\n");
    writeFile(w + "/p.ini",
              "[ViewpointPlan]\nworld_file = landmarks.txt\nmap_file = room.png\n"
              "map_resolution = 0.05\nstart = 0.7 0.7\ngoal = 4.3 2.3\n"
              "\nsafety_margins = 0.05 0.1\n[Robot]\nradius = 0.3\n");
    const std::string out = freshDir("out");
    const json s = planRun(w + "/p.ini", out);
    EXPECT_EQ(s["world"]["obstacles"], 2);
    EXPECT_EQ(s["world"]["landmarks"], 12);
    ASSERT_EQ(s["status"], "ok");
    EXPECT_EQ(s["routes"], 2);  // round the block either way
    for (const auto& sp : s["sweep"])
        for (const auto& p : sp["paths"]) {
            EXPECT_GE(p["min_allowed_error_m"].get<double>(),
                      sp["S"].get<double>() - 1e-9);
            // Never through the block or its 10 cm surroundings.
            for (const auto& v : p["vertices"])
                EXPECT_FALSE(v[0] > 1.9 && v[0] < 3.1 && v[1] > 0.9 && v[1] < 2.1);
        }
}

// Bad input: exit 2, one line naming the problem, earlier results untouched.
namespace {
struct TBad {
    std::string name, world, iniFrom, iniTo, extra, expect;
};
std::ostream& operator<<(std::ostream& o, const TBad& b) {
    return o << b.name;
}
class ViewpointPlanBadInput : public ::testing::TestWithParam<TBad> {};
}  // namespace

TEST_P(ViewpointPlanBadInput, ExitTwoOneLineOutputUntouched) {
    const TBad& c = GetParam();
    const std::string w = freshDir("w");
    std::string world = readFile(sourcePath("datasets/landmarks-two-routes/world.txt"));
    if (!c.world.empty())
        world += c.world;
    writeFile(w + "/world.txt", world);
    std::string ini = readFile(twoRoutes("r1"));
    if (!c.iniFrom.empty()) {
        const std::string e = std::regex_replace(ini, std::regex(c.iniFrom), c.iniTo);
        ASSERT_NE(e, ini) << "edit did not apply";
        ini = e;
    }
    writeFile(w + "/p.ini", ini);
    const std::string out = freshDir("out");
    const TEarlierOutput earlier = {{"summary.json", "{\"earlier\": true}\n"},
                                    {"plan.png", "not really a png"}};
    writeEarlierOutput(out, earlier);
    const auto r = run(binPath("risknav-viewpoint-plan") + " -q -o '" + out + "' " +
                       c.extra + " '" + w + "/p.ini'");
    expectBadInput(r, c.expect, out, earlier, "risknav-viewpoint-plan: error: ");
}

INSTANTIATE_TEST_SUITE_P(
    ViewpointPlan, ViewpointPlanBadInput,
    ::testing::Values(
        TBad{"start_inside_obstacle", "", "start = 0.45 0.6", "start = 2.0 1.2", "",
             "[ViewpointPlan] start = '2.0 1.2': the start (2, 1.2) lies inside an "
             "obstacle"},
        TBad{"goal_too_near", "", "goal = 3.95 0.6", "goal = 3.95 0.2", "",
             "the goal (3.95, 0.2) is nearer an obstacle than the robot radius 0.3 m"},
        TBad{"start_outside", "", "start = 0.45", "start = -3", "",
             "lies inside an obstacle or outside the bounds"},
        TBad{"landmark_inside_obstacle", "landmark X 2.0 1.2 90\n", "", "", "",
             "world.txt:25: landmark 'X' lies inside an obstacle or faces into its wall"},
        TBad{"landmark_facing_wall", "landmark Y 0.0 1.5 180\n", "", "", "",
             "world.txt:25: landmark 'Y' lies inside an obstacle or faces into its wall"},
        TBad{"malformed_polygon", "obstacle 3 3 3.2 3\n", "", "", "",
             "world.txt:25: obstacle: a polygon needs >= 3 vertices"},
        TBad{"self_crossing_polygon", "obstacle 0.2 2.5 0.6 2.9 0.6 2.5 0.2 2.9\n", "",
             "", "", "world.txt:25: obstacle: the polygon is not simple"},
        TBad{"not_a_number", "landmark Z 1.0 3.4 -90 0.05x\n", "", "", "",
             "world.txt:25: landmark: RADIUS '0.05x' is not a decimal number"},
        TBad{"unknown_keyword", "door 1 2 3\n", "", "", "",
             "world.txt:25: unknown keyword 'door'"},
        TBad{"missing_world", "", "world_file = world.txt", "world_file = nowhere.txt",
             "", "nowhere.txt"},
        TBad{"unknown_key", "", "k_paths = 10", "k_paths = 10\nk_path = 3", "",
             "unknown key [ViewpointPlan] k_path"},
        TBad{"unknown_section", "", "\\[Robot\\]", "[Robots]", "",
             "unknown section [Robots]"},
        TBad{"k_paths_zero", "", "k_paths = 10", "k_paths = 0", "",
             "[ViewpointPlan] k_paths = '0': must be in [1, 100]"},
        TBad{"margin_negative", "", "safety_margins = 0.01", "safety_margins = -0.01", "",
             "[ViewpointPlan] safety_margins"},
        TBad{"dead_reckoning_hex", "", "", "", "--set ViewpointPlan.dead_reckoning=0x1",
             "[ViewpointPlan] dead_reckoning"},
        TBad{"focal_zero", "", "\\[Camera\\]", "[Camera]\nfocal_px = 0", "",
             "[Camera] focal_px = '0'"},
        TBad{"goal_equals_start", "", "goal = 3.95 0.6", "goal = 0.45 0.6", "",
             "the goal must differ from the start"},
        TBad{"missing_start", "", "start = 0.45 0.6\n", "", "",
             "[ViewpointPlan] start: required key is missing (x y [m])"},
        TBad{"start_one_number", "", "start = 0.45 0.6", "start = 0.45", "",
             "[ViewpointPlan] start = '0.45': needs exactly 2 numbers"},
        TBad{"old_start_x", "", "start = 0.45 0.6", "start_x = 0.45\nstart_y = 0.6", "",
             "[ViewpointPlan] start_x is now [ViewpointPlan] start = x y"},
        TBad{"landmark_id_with_plus", "landmark A+B 1.0 3.4 -90\n", "", "", "",
             "world.txt:25: landmark: ID 'A+B' must be 1 to 64 of"},
        TBad{"landmark_id_twice", "landmark W0 1.0 3.4 -90\n", "", "", "",
             "world.txt:25: landmark 'W0': the id is given twice"},
        TBad{"facing_huge", "landmark Q 1.0 3.4 1e9\n", "", "", "",
             "FACING_DEG '1e9' is beyond +-1e5 deg"},
        TBad{"margins_twice", "", "safety_margins = 0.01 0.02",
             "safety_margins = 0.02 0.02", "",
             "[ViewpointPlan] safety_margins = '0.02': each margin at most once"}),
    [](const ::testing::TestParamInfo<TBad>& i) { return i.param.name; });

TEST(ViewpointPlanE2E, WorkTheInputCannotJustifyIsRefused) {
    // 400 small triangles: 6400 C-obstacle corner nodes (a quadratic pair
    // loop per S); a 100 km world at 2 cm samples: both exit 2 at once.
    const std::string w = freshDir("w");
    std::string tri = "bounds 0 0 100 100\n";
    for (int i = 0; i < 400; i++) {
        const double x = 5 + (i % 20) * 4.5, y = 5 + (i / 20) * 4.5;
        tri += "obstacle " + std::to_string(x) + " " + std::to_string(y) + " " +
               std::to_string(x + 0.3) + " " + std::to_string(y) + " " +
               std::to_string(x + 0.15) + " " + std::to_string(y + 0.3) + "\n";
    }
    writeFile(w + "/tri.txt", tri);
    writeFile(w + "/huge.txt", "bounds -50000 -50000 50000 50000\n");
    for (const auto& [world, key] :
         {std::pair<std::string, std::string>{"tri.txt", "corner_segments"},
          {"huge.txt", "sample_step"}}) {
        writeFile(w + "/p.ini", "[ViewpointPlan]\nworld_file = " + world +
                                    "\nstart = 1 1\ngoal = 99 99\n");
        const std::string out = freshDir("out");
        const TEarlierOutput earlier = {{"summary.json", "{}\n"}};
        writeEarlierOutput(out, earlier);
        const auto r = run(binPath("risknav-viewpoint-plan") + " -q -o '" + out + "' '" +
                           w + "/p.ini'");
        expectBadInput(r, "[ViewpointPlan] " + key, out, earlier);
    }
}

TEST(ViewpointPlanE2E, WorkOfTheSettingsTogetherIsBoundedToo) {
    // Each within its own range, together they ran 369 s on the 8 x 6 m
    // pillars world: paths x samples, and paths x corner nodes^2.
    const TEarlierOutput earlier = {{"summary.json", "{}\n"}};
    for (const auto& [sets, expect] : std::vector<std::pair<std::string, std::string>>{
             {"--set ViewpointPlan.k_paths=100 --set ViewpointPlan.sample_step=0.001",
              "[ViewpointPlan] k_paths = '100': 9 S x 100 paths x 10000 samples"},
             {"--set ViewpointPlan.k_paths=100 --set ViewpointPlan.corner_segments=360",
              "corner nodes = "}}) {
        const std::string out = freshDir("out");
        writeEarlierOutput(out, earlier);
        const auto r =
            run(binPath("risknav-viewpoint-plan") + " -q -o '" + out + "' " + sets +
                " '" + sourcePath("datasets/landmarks-pillars/r2.ini") + "'");
        expectBadInput(r, expect, out, earlier);
    }
}

TEST(ViewpointPlanE2E, ByteOrderMarkAndCrLfAreAccepted) {
    const std::string w = freshDir("w");
    std::string world = readFile(sourcePath("datasets/landmarks-two-routes/world.txt"));
    world = std::regex_replace(world, std::regex("\n"), "\r\n");
    writeFile(w + "/world.txt", "\xEF\xBB\xBF" + world);
    writeFile(w + "/p.ini", readFile(twoRoutes("r1")));
    const std::string out = freshDir("out");
    const json s = planRun(w + "/p.ini", out);
    const json ref = planRun(twoRoutes("r1"), freshDir("ref"));
    EXPECT_EQ(s["optimal"]["length_m"], ref["optimal"]["length_m"]);
    EXPECT_EQ(s["optimal"]["viewpoints"], ref["optimal"]["viewpoints"]);
}

TEST(ViewpointPlanE2E, BinaryOrHugeWorldFilesAreRefused) {
    const std::string w = freshDir("w");
    writeFile(w + "/world.txt", std::string("bounds 0 0 1 1\n\0\x01\x02", 19));
    writeFile(w + "/p.ini",
              "[ViewpointPlan]\nworld_file = world.txt\nstart = 0.5 0.5\n"
              "goal = 0.6 0.5\n");
    const std::string out = freshDir("out");
    const auto r =
        run(binPath("risknav-viewpoint-plan") + " -q -o '" + out + "' '" + w + "/p.ini'");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("binary data"), std::string::npos) << r.err;
}
