#include <risknav/common/CBadInputError.h>
#include <risknav/common/CCsvWriter.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/CProgress.h>
#include <risknav/common/summary_json.h>

#include <gtest/gtest.h>

#include <limits>

#include <cmath>

#include <filesystem>

#include "test_support.h"

using namespace risknav::common;
using namespace risknav::test;

TEST(COutputDir, FilesAppearOnlyAtCommit) {
    const std::string d = freshDir("out");
    {
        COutputDir out(d);
        out.writeText("a.txt", "new a");
        writeFile(out.stage("b.csv"), "new b");
        ASSERT_EQ(listDir(d).size(), 1u);  // the run's staging folder
        EXPECT_EQ(listDir(d)[0].rfind(".risknav-stage-", 0), 0u);
        EXPECT_FALSE(std::filesystem::exists(d + "/a.txt"));
        out.commit();
    }
    EXPECT_EQ(listDir(d), (std::vector<std::string>{".risknav-run", "a.txt", "b.csv"}));
    EXPECT_EQ(readFile(d + "/a.txt"), "new a");
}

TEST(COutputDir, AFailedRunLeavesEarlierResultsIntact) {
    const std::string d = freshDir("out");
    writeEarlierOutput(d, {{"summary.json", "{\"old\": true}\n"}});
    try {
        COutputDir out(d);
        out.writeText("summary.json", "half-written");
        throw std::runtime_error("crash in the middle");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(listDir(d), (std::vector<std::string>{
                              ".risknav-run", "summary.json"}));  // nothing staged left
    EXPECT_EQ(readFile(d + "/summary.json"), "{\"old\": true}\n");
}

TEST(COutputDir, TemporariesKeepTheExtension) {
    // OpenCV picks the image format from the extension of the temporary name.
    COutputDir out(freshDir("out"));
    EXPECT_EQ(std::filesystem::path(out.stage("world.png")).extension(), ".png");
}

TEST(COutputDir, UnusableFolderIsBadInput) {
    const std::string f = freshDir("x") + "/file";
    writeFile(f, "i am a file");
    EXPECT_THROW(COutputDir out(f), CBadInputError);
}

TEST(WriteFileAtomic, ReplacesWholeFile) {
    const std::string f = freshDir("x") + "/a.txt";
    writeFile(f, "old");
    writeFileAtomic(f, "new content");
    EXPECT_EQ(readFile(f), "new content");
    EXPECT_EQ(listDir(std::filesystem::path(f).parent_path().string()).size(), 1u);
}

TEST(CCsvWriter, HeaderQuotingAndNumbers) {
    const std::string f = freshDir("x") + "/t.csv";
    CCsvWriter csv(f, {"a", "b,c"});
    csv.row({"1", "say \"hi\""});
    csv.row({CCsvWriter::num(0.1 + 0.2), CCsvWriter::fixed(1600000000.25, 3)});
    EXPECT_THROW(csv.row({"only one"}), std::logic_error);
    csv.close();
    EXPECT_EQ(csv.rows(), 2u);
    EXPECT_EQ(readFile(f), "a,\"b,c\"\n1,\"say \"\"hi\"\"\"\n0.3,1600000000.250\n");
}

TEST(CCsvWriter, NoValueIsAnEmptyCellNeverInfOrNan) {
    // ("inf" once reached explore's cycles.csv and risk-eval's table)
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(CCsvWriter::num(inf), "");
    EXPECT_EQ(CCsvWriter::num(-inf), "");
    EXPECT_EQ(CCsvWriter::num(std::nan("")), "");
    EXPECT_EQ(CCsvWriter::fixed(inf, 3), "");
    EXPECT_EQ(CCsvWriter::num(1e308), "1e+308");
}

TEST(CProgress, LineHasCountRateAndEta) {
    EXPECT_EQ(CProgress::formatLine("replay", 50, 200, 10.0, "frames"),
              "replay: 50/200 frames (5 frames/s, ETA 0:30)");
    EXPECT_EQ(CProgress::formatLine("replay", 200, 200, 10.0, "frames"),
              "replay: 200/200 frames in 10.0 s (20 frames/s)");
}

TEST(CProgress, NonTerminalPrintsOneLine) {
    const std::string f = freshDir("x") + "/p.txt";
    FILE* out = std::fopen(f.c_str(), "w");
    {
        CProgress p("work", 10, "items", false, out);
        EXPECT_FALSE(p.isTerminal());
        for (size_t i = 1; i <= 8; i++)
            p.update(i);  // the total was an overestimate
        p.finish();
        p.finish();
    }
    std::fclose(out);
    const auto lines = readLines(f);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].rfind("work: 8/8 items in ", 0), 0u) << lines[0];
}

TEST(COutputDir, CommitIntoASubfolderLeavesTheFolderAlone) {
    const std::string d = freshDir("out");
    writeFile(d + "/zones.csv", "complete run");
    std::filesystem::create_directories(d + "/partial");
    writeFile(d + "/partial/old.csv", "an older partial run");
    writeFile(d + "/.risknav-run",
              "risknav output manifest 2\napp a\nfile zones.csv\ndir "
              "partial\nfile partial/old.csv\n");
    {
        COutputDir out(d);
        out.writeText("zones.csv", "partial run");
        out.commitInto("partial");
        out.commit();
    }
    EXPECT_EQ(readFile(d + "/zones.csv"), "complete run");
    EXPECT_EQ(readFile(d + "/partial/zones.csv"), "partial run");
    EXPECT_FALSE(std::filesystem::exists(d + "/partial/old.csv"));
    EXPECT_EQ(listDir(d),
              (std::vector<std::string>{".risknav-run", "partial", "zones.csv"}));
    EXPECT_EQ(readFile(d + "/.risknav-run"),
              "risknav output manifest 2\napp a\nfile "
              "zones.csv\ndir partial\nfile partial/zones.csv\n");
}

TEST(SummaryJson, NonUtf8TextIsReplacedNotThrown) {
    nlohmann::json j;
    j["route"] = std::string("caf\xe9 \xff route");  // Latin-1, not UTF-8
    const std::string t = jsonText(j);
    EXPECT_NE(t.find("caf\xef\xbf\xbd \xef\xbf\xbd route"), std::string::npos) << t;
    EXPECT_NO_THROW(nlohmann::json::parse(t));
}

TEST(COutputDir, OneRunPerFolderAtATime) {
    const std::string d = freshDir("out");
    {
        COutputDir first(d);
        try {
            COutputDir second(d);
            FAIL() << "a second run got the folder";
        } catch (const CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find("in use by another risknav run"),
                      std::string::npos);
        }
        first.writeText("a.txt", "x");
        first.commit();
    }
    // Released with the first: the folder holds only the results.
    EXPECT_EQ(listDir(d), (std::vector<std::string>{".risknav-run", "a.txt"}));
    EXPECT_NO_THROW(COutputDir again(d));
}

TEST(COutputDir, ACommitThatFailsPutsEverythingBack) {
    const std::string d = freshDir("out");
    writeEarlierOutput(d, {{"a.txt", "earlier a"}, {"b.txt", "earlier b"}});
    const std::string manifest = readFile(d + "/.risknav-run");
    // A step of the commit fails (a rename refused), at every step in turn:
    // the steps done are undone.
    for (int failAt = 1;; failAt++) {
        COutputDir::setCommitStepHook([failAt](int step) {
            if (step == failAt)
                throw std::runtime_error("a rename refused");
        });
        bool failed = false;
        {
            COutputDir out(d);
            out.writeText("a.txt", "new a");
            out.writeText("b.txt", "new b");
            try {
                out.commit();
            } catch (const std::runtime_error&) {
                failed = true;
            }
        }
        COutputDir::setCommitStepHook({});
        if (!failed)
            break;
        EXPECT_EQ(listDir(d),
                  (std::vector<std::string>{".risknav-run", "a.txt", "b.txt"}));
        // a failure after the last rename (removing the staging folder) finds
        // the new set complete; any earlier one the earlier set whole
        if (readFile(d + "/a.txt") == "new a") {
            EXPECT_EQ(readFile(d + "/b.txt"), "new b") << failAt;
            EXPECT_GE(failAt, 9);
            writeEarlierOutput(d, {{"a.txt", "earlier a"}, {"b.txt", "earlier b"}});
            continue;
        }
        EXPECT_LT(failAt, 9);
        EXPECT_EQ(readFile(d + "/a.txt"), "earlier a") << failAt;
        EXPECT_EQ(readFile(d + "/b.txt"), "earlier b") << failAt;
        EXPECT_EQ(readFile(d + "/.risknav-run"), manifest) << failAt;
        ASSERT_LT(failAt, 100);
    }
    EXPECT_EQ(readFile(d + "/a.txt"), "new a");
}

TEST(COutputDir, ASecondRunReplacesTheWholeSetOfTheFirst) {
    // risk-eval's files, then afraid-learn's (or a run with fewer routes): the
    // folder ends with the second run's files only, plus the user's own.
    const std::string d = freshDir("out");
    writeFile(d + "/notes.txt", "the user's own file");
    {
        COutputDir out(d, "risknav-risk-eval");
        out.writeText("summary.json", "risk");
        out.writeText("paths.png", "png");
        out.writeText("ellipses_a.png", "png");
        out.commit();
    }
    EXPECT_NE(
        readFile(d + "/.risknav-run").find("app risknav-risk-eval\nfile summary.json\n"),
        std::string::npos);
    {
        COutputDir out(d, "risknav-afraid-learn");
        out.writeText("summary.json", "afraid");
        out.writeText("zones.csv", "csv");
        out.commit();
    }
    EXPECT_EQ(listDir(d), (std::vector<std::string>{".risknav-run", "notes.txt",
                                                    "summary.json", "zones.csv"}));
    EXPECT_EQ(readFile(d + "/summary.json"), "afraid");
    EXPECT_EQ(readFile(d + "/.risknav-run"),
              "risknav output manifest 2\napp risknav-afraid-learn\nfile summary.json\n"
              "file zones.csv\n");
    // a run that fails in its commit leaves the second run's set whole
    {
        COutputDir out(d, "risknav-risk-eval");
        out.writeText("summary.json", "risk again");
        out.writeText("paths.png", "png");
        std::filesystem::remove(out.stage("paths.png"));
        EXPECT_THROW(out.commit(), std::runtime_error);
    }
    EXPECT_EQ(listDir(d), (std::vector<std::string>{".risknav-run", "notes.txt",
                                                    "summary.json", "zones.csv"}));
    EXPECT_EQ(readFile(d + "/summary.json"), "afraid");
    // a manifest cannot make a run delete outside its folder or hidden files
    writeFile(d + "/.x", "hidden");
    const std::string outside = freshDir("elsewhere") + "/outside.txt";
    writeFile(outside, "outside");
    writeFile(d + "/.risknav-run",
              "risknav output manifest 1\nfile summary.json\nfile .x\nfile "
              "../elsewhere/outside.txt\nfile " +
                  outside + "\n");
    {
        COutputDir out(d);
        out.writeText("summary.json", "third");
        out.commit();
    }
    EXPECT_TRUE(std::filesystem::exists(d + "/.x"));
    EXPECT_TRUE(std::filesystem::exists(outside));
    EXPECT_TRUE(std::filesystem::exists(d + "/zones.csv"));  // not in that manifest
    // nor through a symlinked folder, a subfolder or a symlink to a file (a
    // forged manifest could otherwise delete a file elsewhere)
    const std::string victims = freshDir("victims");
    writeFile(victims + "/precious.txt", "precious");
    writeFile(victims + "/linked.txt", "linked");
    std::filesystem::create_directory_symlink(victims, d + "/link");
    std::filesystem::create_symlink(victims + "/linked.txt", d + "/filelink");
    std::filesystem::create_directory(d + "/sub");
    writeFile(d + "/sub/keep.txt", "user's");
    writeFile(
        d + "/.risknav-run",
        "risknav output manifest 1\nfile summary.json\nfile link/precious.txt\nfile "
        "sub/keep.txt\nfile filelink\n");
    {
        COutputDir out(d);
        out.writeText("summary.json", "fourth");
        out.commit();
    }
    EXPECT_EQ(readFile(victims + "/precious.txt"), "precious");
    EXPECT_EQ(readFile(victims + "/linked.txt"), "linked");
    EXPECT_TRUE(std::filesystem::is_symlink(d + "/filelink"));
    EXPECT_EQ(readFile(d + "/sub/keep.txt"), "user's");
}
