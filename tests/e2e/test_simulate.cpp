// End-to-end: risknav-simulate on the bundled datasets, read back by MRPT's own
// tools (rawlog-edit, pf-localization) as independent clients.
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <sstream>

#include "test_support.h"

using namespace risknav::test;
namespace fs = std::filesystem;

namespace {
std::string simulate(const std::string& world, const std::string& outDir,
                     const std::string& extra = "") {
    const auto r = run(binPath("risknav-simulate") + " -q " + extra + " -o '" + outDir +
                       "' '" + sourcePath("datasets/" + world + "/world.ini") + "'");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");  // --quiet
    return outDir;
}

struct TPoseLine {
    double t, x, y, phi;
};

std::vector<TPoseLine> readPoses(const std::string& f) {
    std::vector<TPoseLine> v;
    for (const auto& l : readLines(f)) {
        if (l.empty() || l[0] == '%')
            continue;
        std::istringstream s(l);
        TPoseLine p{};
        s >> p.t >> p.x >> p.y >> p.phi;
        v.push_back(p);
    }
    return v;
}

// One corridor run per test process (ctest runs each test in its own process).
class CorridorRun : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir = (fs::temp_directory_path() /
               ("risknav-e2e-corridor-" + std::to_string(::getpid())))
                  .string();
        fs::remove_all(dir);
        simulate("corridor-doors", dir);
        summary = readJson(dir + "/summary.json");
    }
    static inline std::string dir;
    static inline nlohmann::json summary;
};
}  // namespace

TEST_F(CorridorRun, SummaryDescribesACompleteSafeRun) {
    EXPECT_EQ(summary["app"], "risknav-simulate");
    EXPECT_EQ(summary["status"], "completed");
    EXPECT_EQ(summary["seed"], 7);
    EXPECT_EQ(summary["laps"], 3);
    EXPECT_EQ(summary["collisions"], 0);
    // 3 laps of 2 x 26 m at 0.2 m/s: 780 s plus turns and stops.
    EXPECT_NEAR(summary["distance_m"].get<double>(), 156.0, 2.0);
    EXPECT_GT(summary["duration_s"].get<double>(), 780.0);
    EXPECT_LT(summary["duration_s"].get<double>(), 900.0);
    EXPECT_GE(summary["emergences"].get<int>(), 3);
    EXPECT_GT(summary["walkers_spawned"].get<int>(), 10);
    EXPECT_GE(summary["min_clearance_agents_m"].get<double>(), 0.0);
    EXPECT_NEAR(summary["min_clearance_static_m"].get<double>(), 1.5 - 0.25 - 0.3,
                0.06);  // pillars
    const auto gt = readPoses(dir + "/groundtruth.txt");
    EXPECT_EQ(gt.size(), summary["frames"].get<size_t>());
    EXPECT_NEAR(gt.back().t - gt.front().t, summary["duration_s"].get<double>(), 1e-6);
    EXPECT_NEAR(gt[1].t - gt[0].t, 0.2, 1e-6);  // 5 Hz
    // Back at the start after whole laps.
    EXPECT_NEAR(gt.back().x, 2.0, 0.15);
    EXPECT_NEAR(gt.back().y, 4.5, 0.05);
    EXPECT_EQ(readPoses(dir + "/odometry.txt").size(), gt.size());
    for (const char* f :
         {"simulation.rawlog", "map.gridmap.gz", "agent_events.csv", "safety_events.csv"})
        EXPECT_TRUE(fs::is_regular_file(dir + "/" + f)) << f;
}

TEST_F(CorridorRun, EventsComeFromTheDoors) {
    const auto lines = readLines(dir + "/agent_events.csv");
    ASSERT_GT(lines.size(), 1u);
    EXPECT_EQ(lines[0], "t,kind,source,agent,x,y");
    int emerge = 0;
    for (const auto& l : lines)
        if (l.find(",emerge,") != std::string::npos) {
            emerge++;
            EXPECT_NE(l.find(",DoorPedestrian"), std::string::npos) << l;
            // People appear behind the door wall (y = 6.6 m), at a door's x.
            EXPECT_NE(l.find(",6.6"), std::string::npos) << l;
        }
    EXPECT_EQ(emerge, summary["emergences"].get<int>());
}

TEST_F(CorridorRun, WorldImageIsAPicture) {
    const cv::Mat img = cv::imread(dir + "/world.png");
    ASSERT_FALSE(img.empty());
    EXPECT_GE(img.cols, 1200);  // 600 cells at 2 px
    EXPECT_GT(img.rows, 400);
}

TEST_F(CorridorRun, RawlogEditReadsTheFrames) {
    const auto r = run("rawlog-edit --info -i '" + dir + "/simulation.rawlog'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const size_t frames = summary["frames"].get<size_t>();
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m,
                                  std::regex("Overall number of objects\\s*:\\s*(\\d+)")))
        << r.out;
    EXPECT_EQ(std::stoul(m[1]), 2 * frames);  // one action + one sensory frame per frame
    EXPECT_NE(r.out.find("Actions/SensoryFrame format       : Yes"), std::string::npos);
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex("LASER /\\s*(\\d+) /([0-9.]+)")))
        << r.out;
    EXPECT_EQ(std::stoul(m[1]), frames);
    EXPECT_NEAR(std::stod(m[2]), 5.0, 1e-3);
}

// MRPT's pf-localization, headless, from a uniform cloud over a 2 x 2 m box
// around the true start (any heading), on our rawlog and map.
TEST_F(CorridorRun, PfLocalizationLocalizesOnIt) {
    const std::string work = freshDir("pf");
    const auto gt = readPoses(dir + "/groundtruth.txt");
    std::ostringstream ini;
    ini << "[KLD_options]\nKLD_binSize_PHI=10\nKLD_binSize_XY=0.10\nKLD_delta=0."
           "01\nKLD_epsilon=0.01\n"
           "KLD_maxSampleSize=40000\nKLD_minSampleSize=150\nKLD_minSamplesPerBin=0\n"
           "[PF_options]\nPF_algorithm=0\nresamplingMethod=0\nadaptiveSampleSize=1\nBETA="
           "0.5\nsampleSize=1\n"
           "[LocalizationExperiment]\nuse_3D_poses=false\n"
        << "map_file=" << dir << "/map.gridmap.gz\nrawlog_file=" << dir
        << "/simulation.rawlog\n"
        << "logOutput_dir=" << work
        << "/LOG\n3DSceneFrequency=-1\nexperimentRepetitions=1\n"
        << "particles_count=20000\ninit_PDF_mode=1\n"
        << "init_PDF_min_x=" << gt[0].x - 1 << "\ninit_PDF_max_x=" << gt[0].x + 1 << "\n"
        << "init_PDF_min_y=" << gt[0].y - 1 << "\ninit_PDF_max_y=" << gt[0].y + 1 << "\n"
        << "SHOW_PROGRESS_3D_REAL_TIME=false\n"
           "[MetricMap]\noccupancyGrid_count=1\nlikelihoodMapSelection=-1\n"
           "[MetricMap_occupancyGrid_00_creationOpts]\nresolution=0.05\n"
           "[MetricMap_occupancyGrid_00_likelihoodOpts]\nlikelihoodMethod=4\nLF_"
           "decimation=5\n"
           "LF_stdHit=0.20\nLF_maxCorrsDistance=0.30\n";
    writeFile(work + "/pf.ini", ini.str());
    const auto r = run("cd '" + work + "' && pf-localization pf.ini");
    ASSERT_EQ(r.exitCode, 0) << r.err.substr(0, 2000);
    const std::regex est("PDF estimation: \\(([-0-9.]+),([-0-9.]+),([-0-9.]+)deg\\)");
    std::vector<std::array<double, 3>> estimates;
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), est);
         it != std::sregex_iterator(); ++it)
        estimates.push_back(
            {std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
    ASSERT_GT(estimates.size(), gt.size() / 2)
        << "pf-localization processed too few frames";
    const auto& last = estimates.back();
    const double err = std::hypot(last[0] - gt.back().x, last[1] - gt.back().y);
    std::cout << "[pf-localization] final estimate (" << last[0] << ", " << last[1]
              << ") vs truth (" << gt.back().x << ", " << gt.back().y << "): error "
              << err << " m\n";
    EXPECT_LT(err, 0.3);
}

TEST(SimulateE2E, SameSeedSameBytesOtherSeedOtherRun) {
    const std::string a = simulate("corridor-doors", freshDir("a"), "--set Route.laps=1");
    const std::string b = simulate("corridor-doors", freshDir("b"), "--set Route.laps=1");
    const std::string c =
        simulate("corridor-doors", freshDir("c"), "--set Route.laps=1 --seed 8");
    ASSERT_EQ(listDir(a), listDir(b));
    for (const auto& f : listDir(a)) {
        if (f == "summary.json")
            continue;
        EXPECT_TRUE(readFile(a + "/" + f) == readFile(b + "/" + f))
            << f << " differs between identical runs";
    }
    auto sa = readJson(a + "/summary.json"), sb = readJson(b + "/summary.json");
    sa.erase("timing");
    sb.erase("timing");
    EXPECT_EQ(sa, sb);
    EXPECT_FALSE(readFile(a + "/simulation.rawlog") ==
                 readFile(c + "/simulation.rawlog"));
    EXPECT_EQ(readJson(c + "/summary.json")["seed"], 8);
    EXPECT_EQ(sa["laps"], 1);
}

TEST(SimulateE2E, OfficeWithTwoSensors) {
    const std::string d = simulate("office", freshDir("office"));
    const auto s = readJson(d + "/summary.json");
    EXPECT_EQ(s["status"], "completed");
    EXPECT_EQ(s["collisions"], 0);
    EXPECT_GE(s["min_clearance_static_m"].get<double>(),
              0.1);  // through the 0.8 m passage
    const size_t frames = s["frames"].get<size_t>();
    ASSERT_EQ(s["sensors"].size(), 2u);
    EXPECT_EQ(s["sensors"][1]["label"], "RANGE2");
    EXPECT_EQ(s["sensors"][1]["scans"].get<size_t>(),
              (frames + 1) / 2);  // every 2nd frame
    const auto r = run("rawlog-edit --info -i '" + d + "/simulation.rawlog'");
    EXPECT_NE(r.out.find("RANGE2"), std::string::npos) << r.out;
    // The robot ends at the last waypoint.
    EXPECT_NEAR(s["end_pose"][0].get<double>(), 2.0, 0.12);
    EXPECT_NEAR(s["end_pose"][1].get<double>(), 11.6, 0.12);
}

TEST(SimulateE2E, CommittedCorridorRawlogIsWhatTheSimulatorWrites) {
    // datasets/corridor-doors/corridor.rawlog is committed for later tools;
    // it must be exactly what the current simulator produces
    // (regenerate with scripts/regen_datasets.sh after changing the simulator).
    const std::string d = simulate("corridor-doors", freshDir("regen"));
    EXPECT_TRUE(readFile(d + "/simulation.rawlog") ==
                readFile(sourcePath("datasets/corridor-doors/corridor.rawlog")))
        << "datasets/corridor-doors/corridor.rawlog is stale: run "
           "scripts/regen_datasets.sh";
    EXPECT_TRUE(readFile(d + "/groundtruth.txt") ==
                readFile(sourcePath("datasets/corridor-doors/corridor_groundtruth.txt")));
}

TEST(SimulateE2E, HelpAndVersion) {
    auto r = run(binPath("risknav-simulate") + " --help");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("usage: risknav-simulate"), std::string::npos);
    r = run(binPath("risknav-simulate") + " --version");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("MRPT 2.5"), std::string::npos);
}

TEST(SimulateE2E, EveryKeyInTheDocumentedConfigIsKnown) {
    // config/risknav-simulate.ini lists every key; the app rejects unknown keys,
    // so a clean run proves the documentation and the code agree. The two
    // optional keys that the file shows commented out are set here.
    const std::string d = freshDir("cfg");
    const auto r = run(binPath("risknav-simulate") + " -q -o '" + d +
                       "' --set Route.speeds=0.3 " + "--set Route.start_heading_deg=0 '" +
                       sourcePath("config/risknav-simulate.ini") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto s = readJson(d + "/summary.json");
    EXPECT_EQ(s["status"], "completed");
    EXPECT_EQ(s["overrides"].size(), 2u);
    // 52 m at 0.3 m/s (the per-segment speed won over speed = 0.2).
    EXPECT_LT(s["duration_s"].get<double>(), 52 / 0.25);
}

TEST(SimulateE2E, MapFormatsGiveTheSameRun) {
    // The same map as a PNG, an MRPT .gridmap.gz and a ROS map_server YAML
    // (three loaders, one of them MRPT's deserializer) must give the same bytes.
    const std::string w = freshDir("maps");
    const std::string png = sourcePath("datasets/corridor-doors/corridor.png");
    writeFile(w + "/corridor.yaml",
              "image: " + png +
                  "\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                  "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
    const std::string laps = "--set Route.laps=1 ";
    const std::string a = simulate("corridor-doors", freshDir("png"), laps);
    const std::string b =
        simulate("corridor-doors", freshDir("gridmap"),
                 laps + "--set World.map_file=" +
                     sourcePath("datasets/corridor-doors/corridor.gridmap.gz"));
    const std::string c = simulate("corridor-doors", freshDir("yaml"),
                                   laps + "--set World.map_file=" + w + "/corridor.yaml");
    const std::string ref = readFile(a + "/simulation.rawlog");
    EXPECT_TRUE(readFile(b + "/simulation.rawlog") == ref)
        << "gridmap.gz differs from PNG";
    EXPECT_TRUE(readFile(c + "/simulation.rawlog") == ref) << "ROS YAML differs from PNG";
}

// MRPT's own dataset map (mrpt-common; serialization version 3, an object
// header without namespace, 1888 x 2738 cells) is a world the simulator
// drives in: loaded (cell for cell as MRPT reads it: MapReaders
// .MrptMalagaCampusGridmapVersion3) and written back as the run's map.
TEST(SimulateE2E, MrptMalagaCampusGridmapIsAWorld) {
    const std::string map = "/usr/share/mrpt/datasets/2006-MalagaCampus.gridmap.gz";
    ASSERT_TRUE(fs::is_regular_file(map)) << "mrpt-common is not installed";
    const std::string w = freshDir("malaga");
    writeFile(w + "/world.ini",
              "[Simulation]\nduration_max = 60\n\n[World]\nmap_file = " + map +
                  "\n\n[Route]\nwaypoints = 4.0 -112.0  10.0 -112.0\n"
                  "speed = 0.5\nlaps = 1\n");
    const std::string out = w + "/out";
    const auto r =
        run(binPath("risknav-simulate") + " -q -o '" + out + "' '" + w + "/world.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const auto s = readJson(out + "/summary.json");
    EXPECT_EQ(s["status"], "completed");
    EXPECT_EQ(s["collisions"], 0);
    EXPECT_GT(s["frames"].get<int>(), 50);
    EXPECT_GT(fs::file_size(out + "/map.gridmap.gz"), 100000u);
}

TEST(SimulateE2E, EffectiveConfigReproducesTheRun) {
    const std::string a =
        simulate("corridor-doors", freshDir("a"), "--set Route.laps=1 --seed 3");
    const auto lines = readLines(a + "/config_effective.ini");
    // "key = value", before the saved "// doc, range" comment
    const auto has = [&](const std::string& l) {
        return std::any_of(lines.begin(), lines.end(), [&](const std::string& x) {
            return x == l || x.rfind(l + " // ", 0) == 0;
        });
    };
    EXPECT_TRUE(has("laps = 1"));        // from --set
    EXPECT_TRUE(has("seed = 3"));        // from --seed
    EXPECT_TRUE(has("max_w_deg = 90"));  // a default the file does not mention
    EXPECT_TRUE(has("map_file = " + sourcePath("datasets/corridor-doors/corridor.png")));
    const std::string b = freshDir("b");
    const auto r = run(binPath("risknav-simulate") + " -q -o '" + b + "' '" + a +
                       "/config_effective.ini'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(readFile(a + "/simulation.rawlog") == readFile(b + "/simulation.rawlog"));
    EXPECT_TRUE(readFile(a + "/agent_events.csv") == readFile(b + "/agent_events.csv"));
}
