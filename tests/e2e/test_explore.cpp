// risknav-explore end to end (M1): the office of datasets/ and
// bad input.
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "test_support.h"

using namespace risknav::test;
namespace fs = std::filesystem;

namespace {
const std::string kApp = "risknav-explore";

struct TRow {
    std::map<std::string, std::string> v;
    double num(const std::string& k) const { return std::stod(v.at(k)); }
};
std::vector<TRow> readCsv(const std::string& path) {
    const auto lines = readLines(path);
    std::vector<std::string> head;
    std::vector<TRow> rows;
    for (size_t i = 0; i < lines.size(); i++) {
        std::vector<std::string> cells;
        std::stringstream ss(lines[i]);
        for (std::string c; std::getline(ss, c, ',');)
            cells.push_back(c);
        if (i == 0) {
            head = cells;
            continue;
        }
        TRow r;
        for (size_t k = 0; k < head.size() && k < cells.size(); k++)
            r.v[head[k]] = cells[k];
        rows.push_back(r);
    }
    return rows;
}

/** The office run, once a process: tests/CMakeLists.txt runs the three tests
 * that read it as one CTest test (ExploreE2E.OfficeRun). */
const std::string& officeRun() {
    static const std::string d = [] {
        const std::string out = freshDir("office");
        const auto r = run(binPath(kApp) + " -q -o '" + out + "' '" +
                           sourcePath("datasets/office/explore.ini") + "'");
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return out;
    }();
    return d;
}
}  // namespace

TEST(ExploreE2E, AdaptiveReachesEverythingSafelyInAFractionOfTheSlowestTime) {
    const auto s = readJson(officeRun() + "/summary.json");
    EXPECT_EQ(s["necessary_observations"], 5);
    const auto& modes = s["modes"];
    ASSERT_EQ(modes.size(), 5u);
    const auto& adaptive = modes[0];
    EXPECT_EQ(adaptive["mode"], "adaptive");
    EXPECT_TRUE(adaptive["all_reached"].get<bool>());
    EXPECT_EQ(adaptive["collisions"], 0);
    EXPECT_GT(adaptive["min_clearance_m"].get<double>(), 0.0);
    const auto& slowest = modes[4];
    EXPECT_EQ(slowest["mode"], "fixed_0.2");
    EXPECT_TRUE(slowest["all_reached"].get<bool>());
    // issue: <= 40 % of the slowest speed's time (paper: 45 s vs 150 s)
    EXPECT_LE(s["adaptive_over_slowest_time"].get<double>(), 0.40);
    // the fastest fixed speed pays for it: a collision or its margin broken
    const auto& fastest = modes[1];
    EXPECT_EQ(fastest["mode"], "fixed_1.1");
    EXPECT_GT(
        fastest["collisions"].get<int>() + fastest["margin_broken_cycles"].get<int>(), 0);
    // the adaptive robot used several speeds, and spent time at the fast ones
    EXPECT_GT(adaptive["time_at_speed_s"]["1.1"].get<double>(), 5.0);
    EXPECT_GT(adaptive["time_at_speed_s"]["0.35"].get<double>(), 2.0);
}

TEST(ExploreE2E, SlowsDownBeforeTheNarrowPassage) {
    // The passage between the desks: x in [4.08, 4.9], y in [10.03, 10.83].
    // Heading there from the door (y ~8.1), the adaptive robot is already at
    // a slow speed for a narrow-space reason before it enters.
    const auto rows = readCsv(officeRun() + "/cycles.csv");
    bool slowBefore = false;
    double fastestInside = 0;
    for (const auto& r : rows) {
        if (r.v.at("mode") != "adaptive")
            continue;
        const double x = r.num("x"), y = r.num("y");
        if (x > 3.8 && x < 5.2 && y > 8.6 && y < 9.9 && r.v.at("reason") == "narrow" &&
            r.num("commanded") <= 0.35)
            slowBefore = true;
        if (x > 4.0 && x < 5.0 && y > 10.0 && y < 10.85)
            fastestInside = std::max(fastestInside, r.num("commanded"));
    }
    EXPECT_TRUE(slowBefore);
    EXPECT_GT(fastestInside, 0.0);   // it went through
    EXPECT_LE(fastestInside, 0.35);  // at a speed whose margin fits
}

TEST(ExploreE2E, OutputsAreThere) {
    const auto files = listDir(officeRun());
    for (const char* f : {"summary.json", "cycles.csv", "trace.png", "speed_profile.png",
                          "config_effective.ini", "snapshots"})
        EXPECT_NE(std::find(files.begin(), files.end(), f), files.end()) << f;
    EXPECT_GE(listDir(officeRun() + "/snapshots").size(), 3u);
    // cycle compute time is measured and plausible (benchmarks give the figure)
    const auto s = readJson(officeRun() + "/summary.json");
    EXPECT_GT(s["modes"][0]["cycle_compute_ms_median"].get<double>(), 0.0);
}

TEST(ExploreE2E, BadInputIsExitTwoWithTheKey) {
    const std::string w = freshDir("w");
    fs::copy_file(sourcePath("datasets/office/office.png"), w + "/office.png");
    const std::string base = readFile(sourcePath("datasets/office/explore.ini"));
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--set Explore.destinations='3 7  6.0 10.4'", "inside an obstacle"},  // a desk
        {"--set Explore.destinations='3 7  25 7'", "outside the world"},
        {"--set Explore.start='0.1 0.1 0'", "[Explore] start"},
        {"--set SpeedControl.speeds='0.7 1.1 0.35 0.2'", "sorted fastest first"},
        {"--set SpeedControl.margins='0.3 0.2 -0.1 0.05'", "[SpeedControl] margins"},
        {"--set SpeedControl.cycle_time=0", "[SpeedControl] cycle_time"},
        {"--set SpeedControl.speeds='1.5 0.7 0.35 0.2'", "exceeds [Robot] max_v"},
        {"--set MapRange2.p_obs_given_free=0.7", "[MapRange2] p_obs_given_obstacle"},
        {"--set Explore.modes=fast", "[Explore] modes"},
        {"--set Explore.memory_size=-1", "[Explore] memory_size"},
        {"--set Explore.memory_resolution=0", "[Explore] memory_resolution"},
        {"--set Explore.memory_size=5", "at least local_map_size"},
        {"--set Explore.memory_size=1e-300", "at least local_map_size"},
        {"--set Explore.memory_resolution=5", "at most local_map_size / 4"},
        {"--set Explore.memory_size=1000 --set Explore.memory_resolution=0.05",
         "more than 4096 memory cells"},
        {"--set SpeedControl.frontier_goal_weight=0.5",
         "[SpeedControl] frontier_goal_weight"},
        {"--set SpeedControl.target_switch_cost=nan",
         "[SpeedControl] target_switch_cost"},
        {"--set SpeedControl.frontier_goal_weight=0x10",
         "(--set): [SpeedControl] frontier_goal_weight = '0x10': not a number"},
        {"--set Explore.not_approaching_timeout=-1", "[Explore] not_approaching_timeout"},
        {"--set Explore.arrival_radius=0.4", "must be at most goal_tolerance = 0.3"},
        {"--set Explore.arrival_radius=0", "[Explore] arrival_radius"},
        {"--set Explore.ego_motion=slam", "[Explore] ego_motion"},
        {"--set ScanMatching.max_correction=-1", "[ScanMatching] max_correction"},
        {"--set ScanMatching.min_goodness=1.5", "[ScanMatching] min_goodness"},
        {"--set ScanMatching.min_match_distance=1", "must be at most match_distance"},
        {"--set ScanMatching.point_sigma=0", "[ScanMatching] point_sigma"},
        {"--set ScanMatching.keyframe_angle=5", "[ScanMatching] keyframe_angle"},
        {"--set MapRange2.p_obs_given_obstacle=0.5001 --set "
         "MapRange2.p_obs_given_free=0.5",
         "[MapRange2] p_obs_given_obstacle = '0.5001': more than 1000 observations"},
        // a start inside a box (a collision in every mode, exit 0),
        // a box off the map
        {"--set Clutter1.x=2.5 --set Clutter1.y=3.2", "is inside [Clutter1]"},
        {"--set Clutter1.x=-5000 --set Clutter1.y=-5000",
         "[Clutter1] x, y: outside the map"},
    };
    writeFile(w + "/explore.ini", base);
    for (const auto& [set, expect] : cases) {
        const std::string out = freshDir("bad");
        const TEarlierOutput earlier = {{"summary.json", "{\"earlier\": true}\n"}};
        writeEarlierOutput(out, earlier);
        const auto r = run(binPath(kApp) + " -q -o '" + out + "' " + set + " '" + w +
                           "/explore.ini'");
        expectBadInput(r, expect, out, earlier, kApp + ": error: ");
    }
}

TEST(ExploreE2E, AnUnreachableDestinationIsReportedAndTheRobotStops) {
    // the office with the upper door walled up: D3 and D4 lie in a room the
    // robot cannot enter
    const std::string w = freshDir("w");
    cv::Mat img =
        cv::imread(sourcePath("datasets/office/office.png"), cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(img.empty());
    // the upper corridor wall (y 8.0 - 8.2) over x 3.5 - 5.5
    cv::rectangle(img, cv::Point(int(3.5 / 0.05), img.rows - int(8.2 / 0.05)),
                  cv::Point(int(5.5 / 0.05), img.rows - int(8.0 / 0.05)), cv::Scalar(0),
                  cv::FILLED);
    cv::imwrite(w + "/office.png", img);
    writeFile(w + "/explore.ini", readFile(sourcePath("datasets/office/explore.ini")));
    const std::string out = freshDir("out");
    const auto r =
        run(binPath(kApp) + " -q -o '" + out + "' --set Explore.modes=adaptive " +
            "--set Explore.destinations='3 7  4.5 8.9' --set Explore.duration_max=120 '" +
            w + "/explore.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto s = readJson(out + "/summary.json");
    EXPECT_EQ(s["status"], "incomplete");
    const auto& m = s["modes"][0];
    EXPECT_EQ(m["destinations"][0], "reached");
    EXPECT_NE(m["destinations"][1], "reached");
    EXPECT_EQ(m["collisions"], 0);
    // an error only where the robot arrived (it was once 0.0 for the missed one)
    EXPECT_TRUE(m["destination_error_m"][0].is_number());
    EXPECT_TRUE(m["destination_error_m"][1].is_null());
    EXPECT_TRUE(m["destination_belief_error_m"][0].is_number());
    EXPECT_TRUE(m["destination_belief_error_m"][1].is_null());
    // no slowest mode here, and no ratio where a mode missed a destination
    EXPECT_TRUE(!s.contains("adaptive_over_slowest_time") ||
                s["adaptive_over_slowest_time"].is_null());
}

TEST(ExploreE2E, ALocalMapOfNoWholeNumberOfCellsDrawsItsSnapshots) {
    // 10 m at 3 cm is 333.3 cells: from this start MRPT's grid for the
    // snapshot images got a cell more a side than the map, and drawing the
    // grown obstacles threw after the whole run (exit 1, no snapshots)
    const std::string out = freshDir("res003");
    const auto r = run(binPath(kApp) + " -q -o '" + out +
                       "' --set Explore.modes=adaptive --set Explore.duration_max=3 " +
                       "--set Explore.local_map_resolution=0.03 " +
                       "--set Explore.start='3.01 3 90' '" +
                       sourcePath("datasets/office/explore.ini") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    int pngs = 0;
    for (const auto& e : fs::directory_iterator(out + "/snapshots"))
        pngs += e.path().extension() == ".png";
    EXPECT_GT(pngs, 0);
}

TEST(ExploreE2E, EveryKeyInTheDocumentedConfigIsKnown) {
    // config/risknav-explore.ini lists every key; the app rejects unknown keys
    const std::string d = freshDir("cfg");
    const auto r = run(binPath(kApp) + " -q -o '" + d +
                       "' --set Explore.modes=adaptive --set Explore.duration_max=20 '" +
                       sourcePath("config/risknav-explore.ini") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto s = readJson(d + "/summary.json");
    EXPECT_EQ(s["necessary_observations"], 5);
    // and config_effective.ini reproduces the run
    const std::string d2 = freshDir("again");
    const auto r2 =
        run(binPath(kApp) + " -q -o '" + d2 + "' '" + d + "/config_effective.ini'");
    ASSERT_EQ(r2.exitCode, 0) << r2.err;
    // (all but compute_ms, the last column: a wall-clock time)
    auto withoutTimes = [](const std::string& path) {
        std::string out;
        for (const auto& l : readLines(path))
            out += l.substr(0, l.rfind(',')) + "\n";
        return out;
    };
    EXPECT_EQ(withoutTimes(d + "/cycles.csv"), withoutTimes(d2 + "/cycles.csv"));
    // and the other way round: every key the app writes is documented there
    const auto documented = iniKeys(sourcePath("config/risknav-explore.ini"));
    for (const auto& k : iniKeys(d + "/config_effective.ini"))
        EXPECT_TRUE(documented.count(k)) << k << " is not in config/risknav-explore.ini";
}

TEST(ExploreE2E, TheTJunctionBeyondTheLocalMapNeedsTheMemory) {
    // datasets/validation: destinations up to 16 m apart, a dead-end branch
    // and a room beside it. With the memory: all four, no collision. With
    // the paper's straight-line rule (memory_size = 0) the robot, back from
    // the branch's dead end, takes the room for the way east and never gets
    // to the third destination.
    const std::string cfg = sourcePath("datasets/validation/explore_t_junction.ini");
    const std::string with = freshDir("tj");
    auto r = run(binPath(kApp) + " -q -o '" + with +
                 "' --set Explore.modes=adaptive --set Explore.duration_max=150 '" + cfg +
                 "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto s = readJson(with + "/summary.json");
    // the robot arrives at all four as it believes; in truth its odometry
    // may have drifted out of goal_tolerance by D3 (seed 1: 0.33 m, its
    // belief 0.29 m off), which is a localization error, not the memory's
    const auto arrived = [](const nlohmann::json& st) {
        return st == "reached" || st == "localization_error";
    };
    for (int k = 0; k < 4; k++)
        EXPECT_TRUE(arrived(s["modes"][0]["destinations"][k])) << k;
    EXPECT_EQ(s["modes"][0]["destinations"][0], "reached");
    EXPECT_EQ(s["modes"][0]["destinations"][1], "reached");
    EXPECT_EQ(s["modes"][0]["collisions"], 0);
    const std::string without = freshDir("tj0");
    r = run(binPath(kApp) + " -q -o '" + without +
            "' --set Explore.modes=adaptive --set Explore.duration_max=150 "
            "--set Explore.memory_size=0 '" +
            cfg + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    s = readJson(without + "/summary.json");
    EXPECT_EQ(s["status"], "incomplete");
    EXPECT_EQ(s["modes"][0]["destinations"][1], "reached");
    // not even in belief
    EXPECT_FALSE(arrived(s["modes"][0]["destinations"][2]));
    EXPECT_TRUE(s["modes"][0]["destination_error_m"][2].is_null());
}

TEST(ExploreE2E, ABeliefThatArrivedWhereTheTruthIsNotIsALocalizationError) {
    // An empty 12 x 12 m room, one destination 6 m ahead, the simulator's
    // default odometry errors (1 mm on the wheels and the tread): the robot
    // drives to where its odometry says the destination is and halts there;
    // in truth it stands 1.5 m away (seed 3). Reached is judged on the true
    // pose: a localization error, with both errors named. With ground-truth
    // ego-motion the same run reaches it, and so it does with the robot's
    // own scan matching (the default), its belief within 0.1 m.
    const std::string w = freshDir("w");
    cv::Mat img(240, 240, CV_8UC1, cv::Scalar(255));
    cv::rectangle(img, cv::Rect(0, 0, 240, 240), cv::Scalar(0), 4);
    cv::imwrite(w + "/room.png", img);
    writeFile(w + "/explore.ini",
              "[Explore]\nstart = 2 6 0\ndestinations = 8 6\nmodes = adaptive\n"
              "duration_max = 60\nseed = 3\n"
              "[World]\nmap_file = room.png\nmap_resolution = 0.05\n"
              "[Robot]\nradius = 0.25\nmax_v = 1.1\n"
              "[Odometry]\nerror_model = systematic\n");
    const std::string drift = freshDir("drift");
    auto r = run(binPath(kApp) + " -q -o '" + drift +
                 "' --set Explore.ego_motion=odometry '" + w + "/explore.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto s = readJson(drift + "/summary.json");
    EXPECT_EQ(s["status"], "incomplete");
    auto m = s["modes"][0];
    EXPECT_EQ(m["destinations"][0], "localization_error");
    EXPECT_FALSE(m["all_reached"].get<bool>());
    EXPECT_EQ(m["destinations_reached"], 0);
    EXPECT_EQ(m["destinations_localization_error"], 1);
    // the belief was within arrival_radius (0.15 m) of the destination: the
    // true distance is the belief's error within that
    const double trueError = m["destination_error_m"][0].get<double>();
    const double beliefError = m["destination_belief_error_m"][0].get<double>();
    EXPECT_GT(trueError, 1.0);
    EXPECT_GT(beliefError, 1.0);
    EXPECT_NEAR(trueError, beliefError, 0.15);
    EXPECT_EQ(m["collisions"], 0);

    const std::string truth = freshDir("truth");
    r = run(binPath(kApp) + " -q -o '" + truth +
            "' --set Explore.ego_motion=ground_truth '" + w + "/explore.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    s = readJson(truth + "/summary.json");
    EXPECT_EQ(s["status"], "ok");
    m = s["modes"][0];
    EXPECT_EQ(m["destinations"][0], "reached");
    EXPECT_LT(m["destination_error_m"][0].get<double>(), 0.3);
    EXPECT_EQ(m["destination_belief_error_m"][0].get<double>(), 0.0);

    const std::string matched = freshDir("matched");
    r = run(binPath(kApp) + " -q -o '" + matched + "' '" + w + "/explore.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    s = readJson(matched + "/summary.json");
    EXPECT_EQ(s["ego_motion"], "scan_matching");
    EXPECT_EQ(s["status"], "ok");
    m = s["modes"][0];
    EXPECT_EQ(m["destinations"][0], "reached");
    EXPECT_LT(m["destination_error_m"][0].get<double>(), 0.3);
    EXPECT_LT(m["destination_belief_error_m"][0].get<double>(), 0.1);
    EXPECT_EQ(m["collisions"], 0);
    EXPECT_GT(m["localization"]["matches_accepted"].get<int>(), 0);
    EXPECT_GT(m["localization"]["map_points"].get<int>(), 0);
}

TEST(ExploreE2E, ADestinationNotApproachedForTheTimeoutIsGivenUp) {
    // the turn on the spot at the start takes ~6 s without coming nearer:
    // with a 4 s alarm the first destination is given up there, the robot
    // goes on to the next
    const std::string out = freshDir("alarm");
    const auto r = run(binPath(kApp) + " -q -o '" + out +
                       "' --set Explore.modes=adaptive --set Explore.duration_max=40 "
                       "--set Explore.not_approaching_timeout=4 '" +
                       sourcePath("datasets/office/explore.ini") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto s = readJson(out + "/summary.json");
    EXPECT_EQ(s["status"], "incomplete");
    EXPECT_EQ(s["modes"][0]["destinations"][0], "unreachable");
    EXPECT_TRUE(s["modes"][0]["destination_error_m"][0].is_null());
    EXPECT_EQ(s["modes"][0]["collisions"], 0);
}
