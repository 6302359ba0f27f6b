// End-to-end: risknav-afraid-learn on simulated corridors (datasets/corridor-doors)
// and on MRPT's own real logs, against MRPT's pf-localization.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "test_support.h"

using namespace risknav::test;
namespace fs = std::filesystem;

namespace {
const std::string kLearn = "risknav-afraid-learn";

// A corridor rawlog from the dataset world: `laps` laps, with or without the
// door pedestrians (the corridor walkers stay), given seed.
std::string simulateCorridor(const std::string& dir, int laps, bool doors, int seed) {
    fs::create_directories(dir);
    fs::copy_file(sourcePath("datasets/corridor-doors/corridor.png"),
                  dir + "/corridor.png", fs::copy_options::overwrite_existing);
    std::ifstream in(sourcePath("datasets/corridor-doors/world.ini"));
    std::ostringstream ini;
    bool skip = false;
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line[0] == '[')
            skip = !doors && line.rfind("[DoorPedestrian", 0) == 0;
        if (!skip)
            ini << line << "\n";
    }
    writeFile(dir + "/world.ini", ini.str());
    const auto r =
        run(binPath("risknav-simulate") + " -q -o '" + dir + "/sim' --seed " +
            std::to_string(seed) + " --set Route.laps=" + std::to_string(laps) + " '" +
            dir + "/world.ini'");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return dir + "/sim";
}

nlohmann::json learn(const std::string& out, const std::string& extra,
                     const std::string& ini = "datasets/corridor-doors/afraid.ini") {
    const auto r = run(binPath(kLearn) + " -q -o '" + out + "' " + extra + " '" +
                       sourcePath(ini) + "'");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readJson(out + "/summary.json");
}

std::string onSim(const std::string& sim) {
    return "--set AfraidLearn.rawlogs=" + sim +
           "/simulation.rawlog --set AfraidLearn.groundtruth_file=" + sim +
           "/groundtruth.txt";
}
}  // namespace

// The paper's experiment: slow laps with people bursting out of three doors.
TEST(AfraidLearnE2E, OneZonePerDoorAndNoOther) {
    const std::string d = freshDir("out");
    const auto s = learn(d, "");
    EXPECT_EQ(s["status"], "ok");
    EXPECT_EQ(s["frames"], 3990);  // 3959 when the vehicle overshot its steps
    const double doors[3][2] = {{11.21, 12.02}, {13.68, 15.10}, {17.53, 18.95}};
    ASSERT_EQ(s["zones"].size(), 3u) << s["zones"].dump();
    std::vector<int> zoneOfDoor(3, 0);
    for (const auto& z : s["zones"]) {
        int hits = 0;
        for (int k = 0; k < 3; k++)
            if (z["x_max"].get<double>() > doors[k][0] &&
                z["x_min"].get<double>() < doors[k][1]) {
                zoneOfDoor[size_t(k)]++;
                hits++;
            }
        EXPECT_EQ(hits, 1) << "zone " << z["id"] << " must overlap exactly one door span";
        EXPECT_GT(z["y_max"].get<double>(), 4.4);  // on the robot's line (y = 4.5)
        EXPECT_LT(z["y_min"].get<double>(), 4.6);
    }
    EXPECT_EQ(zoneOfDoor, (std::vector<int>{1, 1, 1}));
    // The committed rawlog holds 8 door emergences (datasets/README.md): one
    // event each, every one in front of a door.
    EXPECT_EQ(s["events"], 8);
    for (const auto& line : readLines(d + "/events.csv")) {
        if (line.rfind("t,", 0) == 0)
            continue;
        std::stringstream ss(line);
        std::vector<std::string> c;
        for (std::string x; std::getline(ss, x, ',');)
            c.push_back(x);
        const double rx = std::stod(c[3]);
        bool near = false;
        for (const auto& dd : doors)
            near |= rx > dd[0] - 1.0 && rx < dd[1] + 1.0;
        EXPECT_TRUE(near) << line;
    }
    // MCL against the simulator's ground truth.
    const auto& loc = s["localization"];
    std::cout << "[MCL vs ground truth] mean " << loc["mcl_error_mean_m"] << " m, max "
              << loc["mcl_error_max_m"] << " m over " << loc["mcl_error_samples"]
              << " frames\n";
    EXPECT_LT(loc["mcl_error_mean_m"].get<double>(), 0.1);
    // The maximum includes the first frames, converging from a +-1 m, any-heading box.
    EXPECT_LT(loc["mcl_error_max_m"].get<double>(), 1.0);
    EXPECT_FALSE(loc["diverged"].get<bool>());
    for (const char* f :
         {"corridor.afraid", "afraid.png", "profile.png", "zones.csv", "events.csv",
          "trajectory.csv", "speed_mask.pgm", "speed_mask.yaml", "config_effective.ini"})
        EXPECT_TRUE(fs::is_regular_file(d + "/" + f)) << f;
    for (const char* f : {"afraid.png", "profile.png"})
        EXPECT_FALSE(cv::imread(d + "/" + f).empty()) << f;
    // The Nav2 mask: 25 % speed (v_safe / v_max) in the zones, no limit elsewhere.
    const cv::Mat mask = cv::imread(d + "/speed_mask.pgm", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.cols, 600);
    ASSERT_EQ(mask.rows, 200);
    EXPECT_EQ(int(mask.at<uint8_t>(200 - 1 - 90, 0)), 255);  // x = 0, no limit
    int limited = 0;
    for (int x = 0; x < 600; x++)
        limited += mask.at<uint8_t>(200 - 1 - 90, x) != 255;
    EXPECT_GT(limited, 20);
    EXPECT_NE(readFile(d + "/speed_mask.yaml").find("mode: scale"), std::string::npos);
}

TEST(AfraidLearnE2E, NoPedestriansNoEvents) {
    const std::string sim = simulateCorridor(freshDir("w"), 1, false, 3);
    const auto s = learn(freshDir("out"), onSim(sim));
    EXPECT_GT(readJson(sim + "/summary.json")["walkers_spawned"].get<int>(),
              3);  // people, but only expected ones
    EXPECT_EQ(s["events"], 0);
    EXPECT_EQ(s["zones"].size(), 0u);
    EXPECT_EQ(s["status"], "ok");
}

TEST(AfraidLearnE2E, ResumingFromAnAfraidFileEqualsLearningOnBoth) {
    const std::string a = simulateCorridor(freshDir("a"), 1, true, 21),
                      b = simulateCorridor(freshDir("b"), 1, true, 22);
    const std::string outA = freshDir("outA"), outB = freshDir("outB"),
                      outAB = freshDir("outAB");
    // Each rawlog with its own ground truth (one file per rawlog).
    const auto sa = learn(outA, onSim(a));
    const auto sb = learn(
        outB, onSim(b) + " --set AfraidLearn.afraid_in=" + outA + "/corridor.afraid");
    learn(outAB, "--set 'AfraidLearn.rawlogs=" + a + "/simulation.rawlog " + b +
                     "/simulation.rawlog' --set 'AfraidLearn.groundtruth_file=" + a +
                     "/groundtruth.txt " + b + "/groundtruth.txt'");
    EXPECT_EQ(sb["runs_total"], 2);
    EXPECT_EQ(sb["events_total"].get<int>(),
              sa["events"].get<int>() + sb["events"].get<int>());
    // The merged file is byte-identical to learning on both rawlogs in one run.
    EXPECT_TRUE(readFile(outB + "/corridor.afraid") ==
                readFile(outAB + "/corridor.afraid"));
}

// Learning at fleet scale: one .afraid per rawlog, merged in any order, equals
// one run over all the rawlogs, byte for byte; a merge-only run (no rawlog)
// gives the one run's zones and a report without NaN.
TEST(AfraidLearnE2E, MergingPerRawlogFilesInAnyOrderEqualsOneRun) {
    std::vector<std::string> sims, outs;
    std::string rawlogs, truths;
    for (int k = 0; k < 3; k++) {
        sims.push_back(
            simulateCorridor(freshDir("w" + std::to_string(k)), 1, true, 31 + k));
        outs.push_back(freshDir("out" + std::to_string(k)));
        learn(outs.back(), onSim(sims.back()));
        rawlogs += (k ? " " : "") + sims.back() + "/simulation.rawlog";
        truths += (k ? " " : "") + sims.back() + "/groundtruth.txt";
    }
    const std::string all = freshDir("all");
    const auto sAll =
        learn(all, "--set 'AfraidLearn.rawlogs=" + rawlogs +
                       "' --set 'AfraidLearn.groundtruth_file=" + truths + "'");
    ASSERT_EQ(sAll["status"], "ok");
    ASSERT_GT(sAll["events"].get<int>(), 0);  // something to merge
    const auto merge = [&](const std::string& out, const std::vector<int>& order) {
        std::string in;
        for (int k : order)
            in += (in.empty() ? "" : " ") + outs[size_t(k)] + "/corridor.afraid";
        return learn(out,
                     "--set AfraidLearn.rawlogs= --set AfraidLearn.groundtruth_file= "
                     "--set 'AfraidLearn.afraid_in=" +
                         in + "'");
    };
    const std::string m1 = freshDir("m1"), m2 = freshDir("m2");
    const auto s1 = merge(m1, {0, 1, 2});
    const auto s2 = merge(m2, {2, 0, 1});
    const std::string one = readFile(all + "/corridor.afraid");
    ASSERT_FALSE(one.empty());
    EXPECT_TRUE(readFile(m1 + "/corridor.afraid") == one);
    EXPECT_TRUE(readFile(m2 + "/corridor.afraid") == one);
    EXPECT_EQ(s1["runs_total"], 3);
    EXPECT_EQ(s1["events_total"], sAll["events"]);
    // The same zones (and the same mask) as the one run.
    EXPECT_EQ(s1["zones"].dump(), sAll["zones"].dump());
    EXPECT_EQ(s2["zones"].dump(), sAll["zones"].dump());
    EXPECT_GT(s1["zones"].size(), 0u);
    for (const char* f : {"zones.csv", "speed_mask.pgm"})
        EXPECT_TRUE(readFile(m1 + "/" + f) == readFile(all + "/" + f)) << f;
    // Nothing replayed: counts 0, fractions and errors null, no NaN anywhere.
    EXPECT_EQ(s1["status"], "ok");
    EXPECT_EQ(s1["frames"], 0);
    EXPECT_EQ(s1["events"], 0);
    EXPECT_EQ(s1["rawlogs"].size(), 0u);
    EXPECT_EQ(s1["afraid_in"].size(), 3u);
    const auto& loc = s1["localization"];
    EXPECT_EQ(loc["localized_frames"], 0);
    EXPECT_TRUE(loc["localized_fraction"].is_null());
    EXPECT_TRUE(loc["mean_scan_map_agreement"].is_null());
    EXPECT_TRUE(loc["mcl_error_mean_m"].is_null());
    EXPECT_TRUE(loc["final_pose"].is_null());
    EXPECT_FALSE(loc["diverged"].get<bool>());
    EXPECT_TRUE(s1["timing"]["frames_per_s"].is_null());
    const std::string text = readFile(m1 + "/summary.json");
    EXPECT_EQ(text.find("NaN"), std::string::npos);
    EXPECT_EQ(text.find("nan"), std::string::npos);
    EXPECT_EQ(readLines(m1 + "/events.csv").size(), 1u);  // the header only
    EXPECT_EQ(readLines(m1 + "/trajectory.csv").size(), 1u);
    EXPECT_FALSE(cv::imread(m1 + "/afraid.png").empty());
    // A merge-only run over a complete run's folder leaves no route picture of
    // the earlier run behind (it has no route to draw).
    ASSERT_TRUE(fs::is_regular_file(all + "/profile.png"));
    merge(all, {1, 2, 0});
    EXPECT_FALSE(fs::exists(all + "/profile.png"));
    EXPECT_FALSE(fs::exists(all + "/speed.png"));
    EXPECT_TRUE(readFile(all + "/corridor.afraid") == one);
}

// scripts/learn_parallel.sh: one .afraid per rawlog with GNU parallel, then
// the merge; the config's own afraid_in counts once. The same .afraid as one
// run; a failing worker fails the script with one line.
TEST(AfraidLearnE2E, LearnParallelScriptEqualsOneRun) {
    ASSERT_EQ(run("parallel --version | grep -q 'GNU parallel'").exitCode, 0)
        << "GNU parallel is needed (scripts/setup.sh installs it)";
    const std::string a = simulateCorridor(freshDir("a"), 1, true, 41),
                      b = simulateCorridor(freshDir("b"), 1, true, 42),
                      c = simulateCorridor(freshDir("c"), 1, true, 43);
    // An earlier .afraid (rawlog c) named by the config itself.
    const std::string earlier = freshDir("earlier");
    learn(earlier, onSim(c));
    const std::string w = freshDir("w");
    std::string ini = readFile(sourcePath("datasets/corridor-doors/afraid.ini"));
    ini = std::regex_replace(ini, std::regex("corridor\\.gridmap\\.gz"),
                             sourcePath("datasets/corridor-doors/corridor.gridmap.gz"));
    ini = std::regex_replace(
        ini, std::regex("\\[AfraidLearn\\]\n"),
        "[AfraidLearn]\nafraid_in = " + earlier + "/corridor.afraid\n");
    writeFile(w + "/fleet.ini", ini);
    const std::string script = "RISKNAV_LEARN='" + binPath(kLearn) + "' bash '" +
                               sourcePath("scripts/learn_parallel.sh") + "' ";
    const std::string out = freshDir("out") + "/with space";
    const auto r = run(script + "-j 2 '" + w + "/fleet.ini' '" + out + "' '" + a +
                       "/simulation.rawlog' '" + b + "/simulation.rawlog'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string one = freshDir("one");
    const auto rOne =
        run(binPath(kLearn) + " -q -o '" + one + "' --set 'AfraidLearn.rawlogs=" + a +
            "/simulation.rawlog " + b +
            "/simulation.rawlog' --set 'AfraidLearn.groundtruth_file=" + a +
            "/groundtruth.txt " + b + "/groundtruth.txt' '" + w + "/fleet.ini'");
    ASSERT_EQ(rOne.exitCode, 0) << rOne.err;
    const auto sOne = readJson(one + "/summary.json");
    ASSERT_EQ(sOne["runs_total"], 3);
    const auto s = readJson(out + "/summary.json");
    EXPECT_EQ(s["runs_total"], 3);
    EXPECT_EQ(s["zones"].dump(), sOne["zones"].dump());
    EXPECT_TRUE(readFile(out + "/corridor.afraid") == readFile(one + "/corridor.afraid"));
    // Per rawlog (both named simulation.rawlog): its own folder, its ground truth.
    for (const char* k : {"001-simulation", "002-simulation"}) {
        const auto sk = readJson(out + "/per-rawlog/" + k + "/summary.json");
        EXPECT_EQ(sk["rawlogs"].size(), 1u) << k;
        EXPECT_GT(sk["localization"]["mcl_error_samples"].get<int>(), 100) << k;
    }
    // A worker fails (a truncated rawlog): non-zero, one line naming it.
    const std::string full = readFile(b + "/simulation.rawlog");
    writeFile(w + "/cut.rawlog", full.substr(0, full.size() / 2));
    const auto bad = run(script + "'" + w + "/fleet.ini' '" + freshDir("bad") + "' '" +
                         a + "/simulation.rawlog' '" + w + "/cut.rawlog'");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
    EXPECT_NE(bad.err.find("cut.rawlog"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("corrupt or truncated rawlog"), std::string::npos) << bad.err;
}

// config_effective.ini holds every key with the value used (written by the
// options' saveToConfigFile()): the app run on it reproduces the run byte for
// byte, --set, --seed and command-line rawlogs included.
TEST(AfraidLearnE2E, ItsOwnConfigEffectiveReproducesTheRun) {
    const std::string sim = simulateCorridor(freshDir("w"), 1, true, 23);
    const std::string a = freshDir("a");
    // The rawlog on the command line (after the config), not in the file.
    const auto ra = run(binPath(kLearn) + " -q -o '" + a +
                        "' --seed 5 --set AfraidLearn.rawlogs= --set "
                        "AfraidLearn.groundtruth_file=" +
                        sim +
                        "/groundtruth.txt --set Robot.radius=0.3 --set "
                        "AfraidDetector.lateral_margin=0.05 '" +
                        sourcePath("datasets/corridor-doors/afraid.ini") + "' '" + sim +
                        "/simulation.rawlog'");
    ASSERT_EQ(ra.exitCode, 0) << ra.err;
    const auto sa = readJson(a + "/summary.json");
    ASSERT_EQ(sa["status"], "ok");
    const auto lines = readLines(a + "/config_effective.ini");
    // (a line "key = value", or "key = value // doc, range")
    const auto has = [&](const std::string& l) {
        return std::any_of(lines.begin(), lines.end(), [&](const std::string& x) {
            return x == l || x.rfind(l + " //", 0) == 0;
        });
    };
    EXPECT_TRUE(has("seed = 5"));                                 // from --seed
    EXPECT_TRUE(has("rawlogs = " + sim + "/simulation.rawlog"));  // from the command line
    EXPECT_TRUE(has("radius = 0.3"));                             // from --set
    EXPECT_TRUE(has("max_w_deg = 90"));  // a default the file does not mention
    const std::string b = freshDir("b");
    const auto r =
        run(binPath(kLearn) + " -q -o '" + b + "' '" + a + "/config_effective.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : {"events.csv", "zones.csv", "corridor.afraid", "trajectory.csv",
                          "speed_mask.pgm"})
        EXPECT_TRUE(readFile(a + "/" + f) == readFile(b + "/" + f)) << f;
    auto strip = [](nlohmann::json s) {
        for (const char* k : {"timing", "config", "overrides"})
            s.erase(k);
        return s.dump(2);
    };
    EXPECT_EQ(strip(sa), strip(readJson(b + "/summary.json")));
    // ... and writes the same keys again (a fixed point; only the header, which
    // names the source, differs).
    const std::string ea = readFile(a + "/config_effective.ini"),
                      eb = readFile(b + "/config_effective.ini");
    EXPECT_EQ(ea.substr(ea.find("\n[")), eb.substr(eb.find("\n[")));
}

TEST(AfraidLearnE2E, MrptLocalizationDemoMatchesPfLocalization) {
    // MRPT's real log and map; our MCL's final pose vs MRPT's pf-localization
    // on the same rawlog, map and initial box (40000 particles and the box of
    // MRPT's own localization_demo.ini: x in [-10, 10], y in [-15, -5]).
    const std::string w = freshDir("w");
    writeFile(w + "/demo.ini",
              "[AfraidLearn]\nmap_file = "
              "/usr/share/mrpt/datasets/localization_demo.simplemap.gz\n"
              "rawlogs = /usr/share/mrpt/datasets/localization_demo.rawlog\nafraid_name "
              "= demo.afraid\n"
              "[Localization]\nparticles = 40000\ninit_pose = 0 -10 0\ninit_xy = 10 5\n");
    const std::string d = freshDir("out");
    const auto r = run(binPath(kLearn) + " -q -o '" + d + "' '" + w + "/demo.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto s = readJson(d + "/summary.json");
    EXPECT_EQ(s["frames"], 37);
    EXPECT_FALSE(s["localization"]["diverged"].get<bool>());
    writeFile(
        w + "/pf.ini",
        "[KLD_options]\nKLD_binSize_PHI=10\nKLD_binSize_XY=0.10\nKLD_delta=0.01\nKLD_"
        "epsilon=0.01\n"
        "KLD_maxSampleSize=40000\nKLD_minSampleSize=150\nKLD_minSamplesPerBin=0\n"
        "[PF_options]\nPF_algorithm=0\nresamplingMethod=0\nadaptiveSampleSize=1\nBETA=0."
        "5\nsampleSize=1\n"
        "[LocalizationExperiment]\nmap_file=/usr/share/mrpt/datasets/"
        "localization_demo.simplemap.gz\n"
        "rawlog_file=/usr/share/mrpt/datasets/localization_demo.rawlog\nlogOutput_dir=" +
            w +
            "/LOG\n3DSceneFrequency=-1\nparticles_count=40000\ninit_PDF_mode=0\ninit_PDF_"
            "min_x=-10\n"
            "init_PDF_max_x=10\ninit_PDF_min_y=-15\ninit_PDF_max_y=-5\nSHOW_PROGRESS_3D_"
            "REAL_TIME=false\n"
            "[MetricMap]\noccupancyGrid_count=1\n[MetricMap_occupancyGrid_00_"
            "creationOpts]\nresolution=0.05\n"
            "[MetricMap_occupancyGrid_00_likelihoodOpts]\nlikelihoodMethod=4\nLF_"
            "decimation=5\n"
            "LF_stdHit=0.20\nLF_maxCorrsDistance=0.30\n");
    // pf-localization seeds itself from the clock (no seed key) and, from this
    // 20 x 10 m box, ends in the wrong place in about 1 run of 6 (seen here);
    // ours is seeded. So ours must agree with one of up to 5 MRPT runs.
    double best = 1e9;
    for (int attempt = 0; attempt < 5 && best >= 0.2; attempt++) {
        const auto pf = run("cd '" + w + "' && pf-localization pf.ini");
        ASSERT_EQ(pf.exitCode, 0);
        std::smatch m;
        std::string last;
        const std::regex est("PDF estimation: \\(([-0-9.]+),([-0-9.]+),");
        for (auto it = std::sregex_iterator(pf.out.begin(), pf.out.end(), est);
             it != std::sregex_iterator(); ++it)
            last = it->str();
        ASSERT_TRUE(std::regex_search(last, m, std::regex("\\(([-0-9.]+),([-0-9.]+),")));
        const double dx =
            s["localization"]["final_pose"][0].get<double>() - std::stod(m[1]);
        const double dy =
            s["localization"]["final_pose"][1].get<double>() - std::stod(m[2]);
        best = std::min(best, std::hypot(dx, dy));
        std::cout << "[localization_demo] ours vs pf-localization run " << attempt + 1
                  << " final position: " << std::hypot(dx, dy) << " m\n";
    }
    EXPECT_LT(best, 0.2);
}

TEST(AfraidLearnE2E, MalagaSenaWithAMapBuiltByIcpSlam) {
    const std::string w = freshDir("w");
    const std::string rawlog =
        "/usr/share/mrpt/datasets/2006-01ENE-21-SENA_Telecom "
        "Faculty_one_loop_only.rawlog";
    // MRPT's icp-slam builds the map from the same rawlog.
    std::string icp =
        readFile("/usr/share/mrpt/config_files/icp-slam/icp-slam_demo_classic.ini");
    icp = std::regex_replace(icp, std::regex("\nrawlog_file=[^\n]*"),
                             "\nrawlog_file=" + rawlog);
    icp = std::regex_replace(icp, std::regex("\nlogOutput_dir=[^\n]*"),
                             "\nlogOutput_dir=" + w + "/ICP");
    icp = std::regex_replace(icp, std::regex("\nSHOW_PROGRESS_3D_REAL_TIME=1"),
                             "\nSHOW_PROGRESS_3D_REAL_TIME=0");
    icp = std::regex_replace(icp, std::regex("\nSAVE_3D_SCENE=1"), "\nSAVE_3D_SCENE=0");
    writeFile(w + "/icp.ini", icp);
    ASSERT_EQ(run("cd '" + w + "' && icp-slam icp.ini").exitCode, 0);
    ASSERT_TRUE(fs::is_regular_file(w + "/ICP/_finalmap_.simplemap"));
    writeFile(w + "/sena.ini",
              "[AfraidLearn]\nmap_file = ICP/_finalmap_.simplemap\nrawlogs = \"" +
                  rawlog +
                  "\"\nafraid_name = sena.afraid\n[Localization]\nparticles = 5000\n"
                  "init_pose = 0 0 0\ninit_xy = 1\ninit_phi_deg = 20\n");
    const std::string d = freshDir("out");
    const auto r = run(binPath(kLearn) + " -q -o '" + d + "' '" + w + "/sena.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto s = readJson(d + "/summary.json");
    EXPECT_EQ(s["frames"],
              224);  // to the end (the leading sensory frame without action is skipped)
    EXPECT_FALSE(s["localization"]["diverged"].get<bool>());
    EXPECT_GT(s["localization"]["localized_fraction"].get<double>(), 0.95);
    std::cout << "[SENA] localized " << s["localization"]["localized_fraction"]
              << ", scan/map agreement " << s["localization"]["mean_scan_map_agreement"]
              << ", events " << s["events"] << ", zones " << s["zones"].size()
              << ", final pose " << s["localization"]["final_pose"] << "\n";
}

// ---- bad input
TEST(AfraidLearnBadInput, TruncatedRawlogSavesPartialResultsAndKeepsEarlierFiles) {
    const std::string sim = simulateCorridor(freshDir("w"), 1, true, 5);
    const std::string full = readFile(sim + "/simulation.rawlog");
    writeFile(sim + "/cut.rawlog", full.substr(0, full.size() * 6 / 10));
    // A complete earlier run in the output folder, and an earlier .afraid to
    // resume from; a temporary a killed run left behind.
    const std::string out = freshDir("out"), prev = freshDir("prev");
    learn(prev, "--set AfraidLearn.rawlogs=" + sim + "/simulation.rawlog");
    learn(out, "--set AfraidLearn.rawlogs=" + sim + "/simulation.rawlog");
    // (a killed run's staging folder, as its owner marker says)
    fs::create_directories(out + "/.risknav-stage-Kil1ed/new");
    writeFile(out + "/.risknav-stage-Kil1ed/owner", "risknav staging folder 1\n");
    writeFile(out + "/.risknav-stage-Kil1ed/new/zones.csv", "left by a killed run");
    std::map<std::string, std::string> before;
    for (const auto& f : listDir(out))
        if (f.rfind(".risknav-stage-", 0) != 0)
            before[f] = readFile(out + "/" + f);
    const std::string earlier = readFile(prev + "/corridor.afraid");
    const auto r =
        run(binPath(kLearn) + " -q -o '" + out + "' --set AfraidLearn.rawlogs=" + sim +
            "/cut.rawlog --set AfraidLearn.afraid_in=" + prev + "/corridor.afraid '" +
            sourcePath("datasets/corridor-doors/afraid.ini") + "'");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("corrupt or truncated rawlog at entry"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(out + "/partial"), std::string::npos) << r.err;
    // The partial results, apart.
    const auto s = readJson(out + "/partial/summary.json");
    EXPECT_EQ(s["status"], "partial");
    EXPECT_TRUE(s["partial"].get<bool>());
    EXPECT_GT(s["frames"].get<int>(), 100);
    EXPECT_TRUE(fs::is_regular_file(out + "/partial/corridor.partial.afraid"));
    // The complete earlier run: every file as it was, nothing added but
    // partial/ (in the manifest beside the earlier files); the dead run's
    // staging folder is gone.
    for (const auto& [f, content] : before) {
        if (f != ".risknav-run") {
            EXPECT_TRUE(readFile(out + "/" + f) == content) << f;
        }
    }
    EXPECT_EQ(
        readFile(out + "/.risknav-run")
            .rfind(before[".risknav-run"] + "dir partial\nfile partial/afraid.png\n", 0),
        0u);
    auto now = listDir(out);
    now.erase(std::remove(now.begin(), now.end(), "partial"), now.end());
    std::vector<std::string> names;
    for (const auto& [f, c] : before)
        names.push_back(f);
    EXPECT_EQ(now, names);
    EXPECT_TRUE(readFile(prev + "/corridor.afraid") == earlier);
}

TEST(AfraidLearnBadInput, OneGroundTruthPerRawlog) {
    const std::string a = simulateCorridor(freshDir("a"), 1, true, 5);
    const std::string b = simulateCorridor(freshDir("b"), 1, true, 6);
    const std::string two = "--set 'AfraidLearn.rawlogs=" + a + "/simulation.rawlog " +
                            b + "/simulation.rawlog' ";
    // Two rawlogs, one ground truth: refused (the second would be scored
    // against the first one's truth).
    const std::string bad = freshDir("bad");
    const auto r = run(binPath(kLearn) + " -q -o '" + bad + "' " + two +
                       "--set AfraidLearn.groundtruth_file=" + a + "/groundtruth.txt '" +
                       sourcePath("datasets/corridor-doors/afraid.ini") + "'");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("[AfraidLearn] groundtruth_file"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("needs one file per rawlog"), std::string::npos) << r.err;
    // One each: both scored, both listed.
    const auto s =
        learn(freshDir("ok"), two + "--set 'AfraidLearn.groundtruth_file=" + a +
                                  "/groundtruth.txt " + b + "/groundtruth.txt'");
    EXPECT_EQ(s["rawlogs"].size(), 2u);
    EXPECT_LT(s["localization"]["mcl_error_mean_m"].get<double>(), 0.2);
}

TEST(AfraidLearnBadInput, MapRawlogMismatchIsDetected) {
    // A corridor log localized on the office map: MCL cannot agree with it.
    const std::string sim = simulateCorridor(freshDir("w"), 1, false, 4);
    const std::string d = freshDir("out");
    const auto s = learn(d, "--set AfraidLearn.rawlogs=" + sim +
                                "/simulation.rawlog --set AfraidLearn.map_file=" +
                                sourcePath("datasets/office/office.png") +
                                " --set Localization.init_pose=3,3,0 --set "
                                "KLD_options.KLD_maxSampleSize=5000");
    EXPECT_TRUE(s["localization"]["diverged"].get<bool>());
    EXPECT_EQ(s["status"], "diverged");
    EXPECT_LT(s["localization"]["localized_fraction"].get<double>(), 0.5);
}

namespace {
struct TBad {
    std::string name, extra, expect;
};
std::ostream& operator<<(std::ostream& o, const TBad& b) {
    return o << b.name;
}
class AfraidLearnBadArgs : public ::testing::TestWithParam<TBad> {};
}  // namespace

TEST_P(AfraidLearnBadArgs, ExitTwoOneLineOutputUntouched) {
    const auto& c = GetParam();
    const std::string w = freshDir("w");
    writeFile(w + "/text.afraid", "not an afraid file\n");
    if (c.name == "foreign_afraid") {
        // Learned on another map: MRPT's localization demo.
        writeFile(w + "/demo.ini",
                  "[AfraidLearn]\nmap_file = "
                  "/usr/share/mrpt/datasets/localization_demo.simplemap.gz\n"
                  "rawlogs = /usr/share/mrpt/datasets/localization_demo.rawlog\n"
                  "afraid_name = corridor.afraid\n[Localization]\nparticles = "
                  "40000\ninit_pose = 0 -10 0\ninit_xy = 10 5\n");
        const auto r =
            run(binPath(kLearn) + " -q -o '" + w + "/office' '" + w + "/demo.ini'");
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    if (c.name == "no_laser") {
        ASSERT_EQ(run("rawlog-edit --remove-label LASER -i '" +
                      sourcePath("datasets/corridor-doors/corridor.rawlog") + "' -o '" +
                      w + "/nolaser.rawlog'")
                      .exitCode,
                  0);
    }
    const std::string out = freshDir("out");
    const TEarlierOutput earlier = {{"summary.json", "{\"earlier\": true}\n"}};
    writeEarlierOutput(out, earlier);
    std::string extra = std::regex_replace(c.extra, std::regex("@W"), w);
    const auto r = run(binPath(kLearn) + " -q -o '" + out + "' " + extra + " '" +
                       sourcePath("datasets/corridor-doors/afraid.ini") + "'");
    expectBadInput(r, c.expect, out, earlier);
}

INSTANTIATE_TEST_SUITE_P(
    AfraidLearn, AfraidLearnBadArgs,
    ::testing::Values(
        TBad{"unreadable_afraid", "--set AfraidLearn.afraid_in=@W/text.afraid",
             "not a risknav .afraid file"},
        TBad{"foreign_afraid", "--set AfraidLearn.afraid_in=@W/office/corridor.afraid",
             "learned on another map"},
        TBad{"no_laser", "--set AfraidLearn.rawlogs=@W/nolaser.rawlog",
             "no 2D laser scan (CObservation2DRangeScan)"},
        // MRPT's range-bearing logs (they end with an action without its
        // sensory frame): they were called "truncated at entry 500"
        TBad{"mrpt_kf_slam_demo_no_laser",
             "--set AfraidLearn.rawlogs=/usr/share/mrpt/datasets/kf-slam_demo.rawlog",
             "/usr/share/mrpt/datasets/kf-slam_demo.rawlog: no 2D laser scan "
             "(CObservation2DRangeScan) in its first 249 frames, where reading stops: "
             "truncated rawlog at entry 500"},
        TBad{"mrpt_ro_slam_demo_no_laser",
             "--set AfraidLearn.rawlogs=/usr/share/mrpt/datasets/RO-SLAM_demo.rawlog",
             "/usr/share/mrpt/datasets/RO-SLAM_demo.rawlog: no 2D laser scan "
             "(CObservation2DRangeScan) in its first 99 frames"},
        TBad{"missing_rawlog", "--set AfraidLearn.rawlogs=@W/none.rawlog",
             "rawlog not found"},
        TBad{"afraid_in_twice",
             "--set 'AfraidLearn.afraid_in=@W/text.afraid @W/./text.afraid'",
             "given twice"},
        TBad{"no_rawlog_no_afraid_in",
             "--set AfraidLearn.rawlogs= --set AfraidLearn.groundtruth_file=",
             "no rawlog"},
        TBad{"bad_name", "--set AfraidLearn.afraid_name=x.txt",
             "must be a file name ending in .afraid"},
        TBad{"bad_speeds", "--set AfraidLearn.v_safe=1.0", "[AfraidLearn] v_safe"},
        TBad{"unknown_key", "--set AfraidDetector.betta=0.3",
             "unknown key [AfraidDetector] betta"},
        // MRPT's own loaders of these sections took -1 particles as 4e9 (a
        // hang), 'abc' as 0 particles (a silent divergence), KLD_delta 0 to an
        // assert mid-run (exit 1), and refused a [PF_options] given in part
        TBad{"kld_min_negative", "--set KLD_options.KLD_minSampleSize=-1",
             "[KLD_options] KLD_minSampleSize = '-1': must be in [1, 1e+06]"},
        TBad{"kld_max_text", "--set KLD_options.KLD_maxSampleSize=abc",
             "[KLD_options] KLD_maxSampleSize = 'abc': not an integer"},
        TBad{"kld_delta_zero", "--set KLD_options.KLD_delta=0",
             "[KLD_options] KLD_delta = '0': must be in (0, 1)"},
        TBad{"kld_max_below_min", "--set KLD_options.KLD_maxSampleSize=100",
             "must be at least KLD_minSampleSize = 150"},
        TBad{"pf_algorithm_unknown", "--set PF_options.PF_algorithm=pfFoo",
             "[PF_options] PF_algorithm = 'pfFoo': must be one of: pfStandardProposal"},
        TBad{"pf_beta_nan", "--set PF_options.BETA=nan", "[PF_options] BETA = 'nan'"},
        // Too few start particles for the initial region lost the robot, and
        // the lost filter ran at KLD_maxSampleSize every frame (~25x the time).
        TBad{
            "particles_below_region", "--set Localization.particles=200",
            "[Localization] particles = '200': must be in [1513, 1e+06] for init = pose"},
        TBad{"particles_below_map", "--set Localization.init=global",
             "[Localization] particles = '5000': must be in [45256, 1e+06] for init = "
             "global"}),
    [](const ::testing::TestParamInfo<TBad>& i) { return i.param.name; });

TEST(AfraidLearnE2E, GroundTruthIsReadStrictly) {
    // a NaN line and a file of another run (every time 1e6 s
    // later) were dropped in silence (mcl_error_samples 182 of 183, and 0)
    const std::string w = freshDir("w");
    ASSERT_EQ(run("rawlog-edit --cut --to-index 100 -i '" +
                  sourcePath("datasets/corridor-doors/corridor.rawlog") + "' -o '" + w +
                  "/short.rawlog'")
                  .exitCode,
              0);
    const auto lines =
        readLines(sourcePath("datasets/corridor-doors/corridor_groundtruth.txt"));
    std::string nanLine, shifted;
    for (size_t i = 0; i < lines.size(); i++) {
        if (lines[i].empty() || lines[i][0] == '%')
            continue;
        std::istringstream ls(lines[i]);
        double t = 0, x = 0, y = 0, phi = 0;
        ls >> t >> x >> y >> phi;
        char b[120];
        std::snprintf(b, sizeof(b), "%.3f %.6f %.6f %.6f\n", t + 1e6, x, y, phi);
        shifted += b;
        nanLine += i == 4 ? "1600000000.8 nan 4.5 0\n" : lines[i] + "\n";
    }
    writeFile(w + "/nan.txt", nanLine);
    writeFile(w + "/shifted.txt", shifted);
    for (const auto& [file, expect] : std::vector<std::pair<std::string, std::string>>{
             {"nan.txt",
              "nan.txt:4: expected 't x y phi' (4 numbers), got "
              "'1600000000.8 nan 4.5 0'"},
             {"shifted.txt", "shifted.txt: no line's time matches a frame of"}}) {
        const std::string out = freshDir("out");
        const TEarlierOutput earlier = {{"summary.json", "{\"earlier\": true}\n"}};
        writeEarlierOutput(out, earlier);
        const auto r =
            run(binPath(kLearn) + " -q -o '" + out + "' --set AfraidLearn.rawlogs='" + w +
                "/short.rawlog' --set AfraidLearn.groundtruth_file='" + w + "/" + file +
                "' --set Localization.particles=1000 --set Localization.init_xy=0.5 '" +
                sourcePath("datasets/corridor-doors/afraid.ini") + "'");
        expectBadInput(r, expect, out, earlier);
    }
}

TEST(AfraidLearnE2E, APartPfOptionsSectionTakesTheOtherDefaults) {
    // MRPT's loader demanded every key of a [PF_options] given in part (exit 1)
    const auto s = learn(freshDir("out"), "--set PF_options.BETA=0.5");
    EXPECT_EQ(s["status"], "ok");
    EXPECT_EQ(s["zones"].size(), 3u);
}

TEST(AfraidLearnE2E, EveryKeyInTheDocumentedConfigIsKnown) {
    // (the optional afraid_in is exercised by the resume test)
    const auto s = learn(freshDir("out"), "--set AfraidLearn.scan_label=LASER",
                         "config/risknav-afraid-learn.ini");
    EXPECT_EQ(s["status"], "ok");
    EXPECT_EQ(s["zones"].size(), 3u);
    // The paper's 10 m comparison (51.3 s before vs 24.3 s after learning):
    // ours starts 1 m before the first zone.
    EXPECT_NEAR(s["ten_metre_section"]["time_before_s"].get<double>(), 50.0, 1e-6);
    EXPECT_LT(s["ten_metre_section"]["time_after_s"].get<double>(), 35.0);
}

// Paths and names quoted in a message are clipped as config values are: a
// 100 KB sensor label was quoted whole on the "one line".
TEST(AfraidLearnMessages, LongNameIsClipped) {
    const std::string label(100000, 'L');
    const std::string out = freshDir("out");
    const auto r =
        run(binPath(kLearn) + " -q -o '" + out +
            "' --set AfraidLearn.rawlogs=/usr/share/mrpt/datasets/"
            "kf-slam_demo.rawlog --set AfraidLearn.scan_label=" +
            label + " '" + sourcePath("datasets/corridor-doors/afraid.ini") + "'");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err.size();
    EXPECT_LT(r.err.size(), 600u);
    EXPECT_NE(r.err.find("labelled 'LLLL"), std::string::npos);
    EXPECT_NE(r.err.find("... (100000 bytes)') in its first 249 frames"),
              std::string::npos)
        << r.err.substr(0, 300);
}
