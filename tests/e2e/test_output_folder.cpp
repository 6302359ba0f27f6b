// The apps and their output folder: nothing of the user's is replaced, moved
// or written through, a full disk is one line naming the file (exit 1), and
// a killed run leaves nothing the next run cannot clean.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "test_support.h"

using namespace risknav::test;
namespace fs = std::filesystem;

namespace {
std::string app(const std::string& name, const std::string& config) {
    return binPath("risknav-" + name) + " -q '" + sourcePath("config/" + config) + "'";
}

int countLines(const std::string& s) {
    return int(std::count(s.begin(), s.end(), '\n'));
}

bool hasStagingFolder(const std::string& dir) {
    for (const auto& n : listDir(dir))
        if (n.rfind(".risknav-stage-", 0) == 0)
            return true;
    return false;
}
}  // namespace

TEST(OutputFolder, ARunNeverReplacesItsOwnInputMap) {
    // `-o .` in the folder of the map world.png: the picture would replace it
    const std::string d = freshDir("here");
    fs::copy_file(sourcePath("datasets/corridor-doors/corridor.png"), d + "/world.png");
    const std::string map = readFile(d + "/world.png");
    const TRun r = run(app("simulate", "risknav-simulate.ini") + " -o '" + d +
                       "' --set World.map_file='" + d + "/world.png'");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("world.png: is an input of this run"), std::string::npos)
        << r.err;
    EXPECT_EQ(readFile(d + "/world.png"), map);
    EXPECT_EQ(listDir(d), (std::vector<std::string>{"world.png"}));
}

TEST(OutputFolder, ASnapshotsFolderThatIsNotTheRunsIsRefusedBeforeTheRun) {
    const std::string victim = freshDir("elsewhere");
    writeFile(victim + "/cycle_0000.png", "the user's picture");
    for (const bool asLink : {true, false}) {
        const std::string d = freshDir(asLink ? "link" : "file");
        if (asLink)
            fs::create_directory_symlink(victim, d + "/snapshots");
        else
            writeFile(d + "/snapshots", "a file");
        const TRun r = run(app("explore", "risknav-explore.ini") + " -o '" + d + "'");
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(
            r.err.find(asLink ? "/snapshots: a symbolic link or special file (risknav "
                                "writes none)"
                              : "/snapshots: a file that no risknav run wrote"),
            std::string::npos)
            << r.err;
        EXPECT_EQ(listDir(d), (std::vector<std::string>{"snapshots"}));
    }
    EXPECT_EQ(listDir(victim), (std::vector<std::string>{"cycle_0000.png"}));
    EXPECT_EQ(readFile(victim + "/cycle_0000.png"), "the user's picture");
}

TEST(OutputFolder, ARerunReplacesTheEarlierRunsSnapshotsWhole) {
    // an earlier explore run's 32 snapshots, as its manifest lists them
    const std::string d = freshDir("out");
    fs::create_directories(d + "/snapshots");
    std::string manifest =
        "risknav output manifest 2\napp risknav-explore\ndir snapshots\n";
    for (int i = 0; i < 32; i++) {
        const std::string name = "cycle_" + std::to_string(9000 + i) + ".png";
        writeFile(d + "/snapshots/" + name, "old");
        manifest += "file snapshots/" + name + "\n";
    }
    writeFile(d + "/.risknav-run", manifest);
    // (the adaptive mode writes the snapshots: the fixed ones are not needed)
    const TRun r = run(app("explore", "risknav-explore.ini") + " -o '" + d +
                       "' --set Explore.modes=adaptive");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto snaps = listDir(d + "/snapshots");
    ASSERT_FALSE(snaps.empty());
    for (const auto& s : snaps)
        EXPECT_LT(s, "cycle_9000.png") << "an earlier run's snapshot is left";
    const auto lines = readLines(d + "/.risknav-run");
    EXPECT_NE(std::find(lines.begin(), lines.end(), "dir snapshots"), lines.end());
}

TEST(OutputFolder, AFullDiskIsOneLineNamingTheFileAndEarlierResultsStay) {
    // The file size limit makes writes fail as a full disk does (EFBIG).
    for (const auto& [name, config] :
         {std::pair<std::string, std::string>{"navigate", "risknav-navigate.ini"},
          {"simulate", "risknav-simulate.ini"},
          {"risk-eval", "risknav-risk-eval.ini"}}) {
        const std::string d = freshDir(name);
        const TEarlierOutput earlier{{"summary.json", "{\"earlier\": true}\n"},
                                     {"notes.txt", "an earlier result"}};
        writeEarlierOutput(d, earlier);
        const TRun r =
            run("trap '' XFSZ; ulimit -f 100; " + app(name, config) + " -o '" + d + "'");
        EXPECT_EQ(r.exitCode, 1) << name << ": " << r.err;
        EXPECT_EQ(countLines(r.err), 1) << name << ": " << r.err;
        EXPECT_EQ(r.err.rfind(
                      "risknav-" + name + ": runtime error: cannot write " + d + "/", 0),
                  0u)
            << r.err;
        EXPECT_NE(r.err.find(": File too large"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find(".risknav-stage-"), std::string::npos) << r.err;
        std::vector<std::string> names{".risknav-run", "notes.txt", "summary.json"};
        EXPECT_EQ(listDir(d), names) << name;
        EXPECT_EQ(readFile(d + "/summary.json"), "{\"earlier\": true}\n");
    }
}

TEST(OutputFolder, AKilledRunLeavesNothingTheNextRunCannotClean) {
    const std::string d = freshDir("out");
    // killed while it works (or, on a fast machine, after it ends: the
    // folder is then whole either way)
    run("timeout -s KILL 0.8 " + app("navigate", "risknav-navigate.ini") + " -o '" + d +
        "'");
    const TRun r = run(app("navigate", "risknav-navigate.ini") + " -o '" + d + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(hasStagingFolder(d));
    EXPECT_TRUE(fs::exists(d + "/summary.json"));
    for (const auto& n : listDir(d))
        EXPECT_NE(n[0] == '.' && n != ".risknav-run", true) << n;
}
