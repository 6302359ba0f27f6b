// End-to-end: config names that become file names, the same input file given
// twice, and config_effective.ini of a run whose paths hold MRPT preprocessor
// text. Each bad case: exit 2, one line naming file, section and key, and an
// earlier output left as it was.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_support.h"

using namespace risknav::test;
namespace fs = std::filesystem;

namespace {
const TEarlierOutput kEarlier = {{"summary.json", "{\"earlier\": true}\n"}};

TRun riskEval(const std::string& out, const std::string& ini,
              const std::string& extra = "") {
    return run(binPath("risknav-risk-eval") + " -q -o '" + out + "' " + extra + " '" +
               ini + "'");
}

TRun afraidLearn(const std::string& out, const std::string& extra) {
    return run(binPath("risknav-afraid-learn") + " -q -o '" + out + "' " + extra + " '" +
               sourcePath("datasets/corridor-doors/afraid.ini") + "'");
}
}  // namespace

TEST(ConfigNamesE2E, RiskEvalRefusesRoutesWhoseFilesWouldCollide) {
    const std::string ini = sourcePath("datasets/risk-two-routes/risk.ini");
    const std::string out = freshDir("out");
    writeEarlierOutput(out, kEarlier);
    const auto r = riskEval(out, ini, "--set 'Route1.name=a b' --set Route2.name=a_b");
    expectBadInput(r,
                   "risk.ini (--set): [Route2] name = 'a_b': its files cov_a_b.csv and "
                   "ellipses_a_b.png would be those of [Route1] name = 'a b'",
                   out, kEarlier);
    // a config route named as a GVG route (risk.ini has gvg_routes = 3)
    const auto g = riskEval(out, ini, "--set Route1.name=G3");
    expectBadInput(g, "would be those of GVG route G3", out, kEarlier);
}

TEST(ConfigNamesE2E, NamesTooLongForTheFileSystemAreRefusedBeforeTheWork) {
    const std::string ini = sourcePath("datasets/risk-two-routes/risk.ini");
    const std::string out = freshDir("out");
    writeEarlierOutput(out, kEarlier);
    const std::string longName(300, 'r');
    expectBadInput(riskEval(out, ini, "--set Route1.name=" + longName),
                   "[Route1] name = '", out, kEarlier);
    expectBadInput(
        afraidLearn(out, "--set AfraidLearn.afraid_name=" + longName + ".afraid"),
        "[AfraidLearn] afraid_name = '", out, kEarlier);
    const auto a =
        afraidLearn(out, "--set AfraidLearn.afraid_name=" + longName + ".afraid");
    EXPECT_NE(a.err.find("bytes long; at most 235"), std::string::npos) << a.err;
}

TEST(ConfigNamesE2E, AfraidLearnComparesInputFilesByIdentity) {
    const std::string w = freshDir("w");
    const std::string rawlog = sourcePath("datasets/corridor-doors/corridor.rawlog");
    fs::create_symlink(rawlog, w + "/sym.rawlog");
    // a hard link needs the same file system: a copy of the rawlog in w
    fs::copy_file(rawlog, w + "/copy.rawlog");
    fs::create_hard_link(w + "/copy.rawlog", w + "/hard.rawlog");
    writeFile(w + "/a.afraid", "x");
    fs::create_hard_link(w + "/a.afraid", w + "/b.afraid");
    const std::string out = freshDir("out");
    writeEarlierOutput(out, kEarlier);
    struct TCase {
        std::string extra, expect;
    };
    for (const TCase& c :
         {TCase{"--set 'AfraidLearn.rawlogs=corridor.rawlog ./corridor.rawlog'",
                "[AfraidLearn] rawlogs = '" +
                    fs::path(rawlog).lexically_normal().string() +
                    "': entry 2 given twice: the same file as entry 1"},
          TCase{"--set 'AfraidLearn.rawlogs=corridor.rawlog " + w + "/sym.rawlog'",
                "entry 2 given twice: the same file as entry 1"},
          TCase{"--set 'AfraidLearn.rawlogs=" + w + "/copy.rawlog " + w + "/hard.rawlog'",
                "[AfraidLearn] rawlogs = '" + w +
                    "/hard.rawlog': entry 2 given twice: the same file as entry 1 '" + w +
                    "/copy.rawlog'"},
          TCase{"--set 'AfraidLearn.afraid_in=" + w + "/a.afraid " + w + "/b.afraid'",
                "[AfraidLearn] afraid_in = '" + w +
                    "/b.afraid': entry 2 given twice: the same file as entry 1"}})
        expectBadInput(afraidLearn(out, c.extra), c.expect, out, kEarlier);
}

// config_effective.ini holds resolved paths and names the source config: in
// a folder named with MRPT's preprocessor syntax it must still load back and
// reproduce the run.
TEST(ConfigNamesE2E, ConfigEffectiveWithPreprocessorTextInPathsReproducesTheRun) {
    const std::string dir = freshDir("eff") + "/cfg ${HOME} $eval{1+1} @define X";
    fs::create_directories(dir);
    fs::copy_file(sourcePath("datasets/risk-two-routes/risk.ini"), dir + "/risk.ini");
    fs::copy_file(sourcePath("datasets/risk-two-routes/two_routes.png"),
                  dir + "/two_routes.png");
    // (the copied config itself holds no such text: the folder does)
    const std::string a = freshDir("a");
    const auto ra = riskEval(a, dir + "/risk.ini", "--set RiskEval.gvg_routes=0");
    ASSERT_EQ(ra.exitCode, 0) << ra.err;
    const std::string b = freshDir("b");
    const auto rb = riskEval(b, a + "/config_effective.ini");
    ASSERT_EQ(rb.exitCode, 0) << rb.err;
    EXPECT_EQ(readFile(a + "/risk_table.csv"), readFile(b + "/risk_table.csv"));
    EXPECT_EQ(readJson(b + "/summary.json")["map"]["file"],
              readJson(a + "/summary.json")["map"]["file"]);
    EXPECT_NE(readJson(b + "/summary.json")["map"]["file"].get<std::string>().find(
                  "cfg ${HOME} $eval{1+1} @define X/two_routes.png"),
              std::string::npos);
}
