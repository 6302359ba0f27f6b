// The output folder's rules: nothing of the user's is lost or touched, no
// write goes outside the folder, and a commit is all-or-nothing across a kill
// at any instant.
#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/config_read.h>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <functional>

#include "test_support.h"

namespace fs = std::filesystem;
using namespace risknav::common;
using namespace risknav::test;

namespace {
// Every file under `dir` (relative path -> content), symlinks as "-> target".
std::map<std::string, std::string> tree(const std::string& dir) {
    std::map<std::string, std::string> t;
    for (auto it = fs::recursive_directory_iterator(dir); it != fs::end(it); ++it) {
        const std::string rel = fs::path(it->path()).lexically_relative(dir).string();
        if (it->is_symlink())
            t[rel] = "-> " + fs::read_symlink(it->path()).string();
        else if (it->is_regular_file())
            t[rel] = readFile(it->path().string());
        else
            t[rel + "/"] = "";
    }
    return t;
}

std::string expectBadInputFrom(const std::function<void()>& f) {
    try {
        f();
    } catch (const CBadInputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no CBadInputError";
    return "";
}

// Runs `work` in a child process (a run that may be killed, or that changes
// its own limits) and returns how it ended: its exit code, or -signal.
int inChild(const std::function<int()>& work) {
    const pid_t pid = fork();
    if (pid == 0)
        _exit(work());
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) != pid)
        return -1000;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// The file size limit makes writes fail as a full disk does (EFBIG).
void limitFileSize(rlim_t bytes) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit lim{bytes, bytes};
    setrlimit(RLIMIT_FSIZE, &lim);
}

// An app's run, as the apps write: files, a subfolder of snapshots, a
// scratch folder.
void writeRun(COutputDir& out, const std::string& tag, int snapshots) {
    out.writeText("summary.json", "summary " + tag);
    out.writeText("cycles.csv", "cycles " + tag);
    for (int i = 0; i < snapshots; i++)
        writeFile(out.stage("snapshots/cycle_" + std::to_string(i) + ".png"),
                  "png " + tag + std::to_string(i));
    writeFile(out.scratchDir("navlog") + "/log_000.reactivenavlog", "scratch " + tag);
}
}  // namespace

TEST(OutputRules, TemporariesAreCreatedExclusivelyInTheRunsOwnFolder) {
    const std::string d = freshDir("out");
    const std::string victim = freshDir("elsewhere") + "/precious.txt";
    writeFile(victim, "precious");
    // symlinks planted at every name an earlier version would have used
    for (const char* n : {"summary.json", "world.png", "navlog", "snapshots"})
        fs::create_symlink(victim, d + "/.tmp-" + std::to_string(::getpid()) + "-" + n);
    {
        COutputDir out(d, "risknav-test");
        const std::string p = out.stage("world.png");
        // a new, empty regular file inside the staging folder, named as the
        // result (OpenCV picks the format from the extension)
        EXPECT_NE(p.find("/.risknav-stage-"), std::string::npos) << p;
        EXPECT_EQ(fs::path(p).filename(), "world.png");
        EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(p)));
        EXPECT_EQ(fs::file_size(p), 0u);
        EXPECT_EQ(fs::status(fs::path(p).parent_path().parent_path()).permissions() &
                      fs::perms::others_write,
                  fs::perms::none);
        writeFile(p, "png");
        out.writeText("summary.json", "{}");
        writeRun(out, "a", 2);
        out.commit();
    }
    EXPECT_EQ(readFile(victim), "precious");
    EXPECT_EQ(readFile(d + "/world.png"), "png");
    // the planted links are not the run's: left as they are
    EXPECT_TRUE(
        fs::is_symlink(d + "/.tmp-" + std::to_string(::getpid()) + "-summary.json"));
    // a writer's error names the final file, not the staging folder
    EXPECT_EQ(shownOutputPath(d + "/.risknav-stage-Ab12Cd/new/snapshots/x.png"),
              d + "/snapshots/x.png");
}

TEST(OutputRules, AnOutputFolderThatIsASymlinkIsRefused) {
    const std::string target = freshDir("target");
    const std::string link = freshDir("links") + "/out";
    fs::create_directory_symlink(target, link);
    const std::string msg = expectBadInputFrom([&] { COutputDir out(link); });
    EXPECT_NE(msg.find("symbolic link"), std::string::npos) << msg;
    EXPECT_TRUE(fs::is_empty(target));
}

TEST(OutputRules, NamesTheFileSystemCannotHoldAreBadInput) {
    const std::string d = freshDir("out") + "/" + std::string(300, 'n');
    const std::string msg = expectBadInputFrom([&] { COutputDir out(d); });
    EXPECT_NE(msg.find("a folder name of 300 bytes"), std::string::npos) << msg;
    EXPECT_LT(msg.size(), 400u) << "the 300-byte name is quoted clipped";
}

TEST(OutputRules, WhatNoRunWroteIsNeverReplacedNorMoved) {
    const std::string d = freshDir("out");
    // the user's folder and file that carry output names, and a symlink
    fs::create_directories(d + "/world.png");
    writeFile(d + "/world.png/keep.txt", "user's");
    writeFile(d + "/cycles.csv", "the user's own table");
    const std::string elsewhere = freshDir("elsewhere");
    writeFile(elsewhere + "/user.png", "user's");
    fs::create_directory_symlink(elsewhere, d + "/snapshots");
    const auto before = tree(d);
    // named to the constructor: refused before the work
    for (const char* name : {"world.png", "cycles.csv", "snapshots/cycle_1.png"}) {
        const std::string msg =
            expectBadInputFrom([&] { COutputDir out(d, "risknav-test", {name}); });
        EXPECT_NE(msg.find(std::string(name).rfind("snapshots", 0) == 0
                               ? "a symbolic link or special file (risknav writes none)"
                               : "that no risknav run wrote is in the way of an output"),
                  std::string::npos)
            << msg;
    }
    // met at stage(): refused there, before anything is committed
    {
        COutputDir out(d, "risknav-test");
        out.writeText("summary.json", "{}");
        EXPECT_THROW(out.stage("world.png"), CBadInputError);
        EXPECT_THROW(out.stage("cycles.csv"), CBadInputError);
        const std::string msg =
            expectBadInputFrom([&] { out.stage("snapshots/cycle_0001.png"); });
        EXPECT_NE(msg.find("a symbolic link"), std::string::npos) << msg;
    }
    EXPECT_EQ(tree(d), before);
    EXPECT_EQ(readFile(elsewhere + "/user.png"), "user's");
    // a subfolder in the way as a file is refused alike (it was exit 1 after
    // the whole run)
    const std::string d2 = freshDir("out2");
    writeFile(d2 + "/snapshots", "a file");
    EXPECT_THROW(COutputDir(d2, "risknav-explore", {"snapshots/"}), CBadInputError);
    EXPECT_EQ(readFile(d2 + "/snapshots"), "a file");
}

TEST(OutputRules, AnInputOfTheRunIsNeverReplaced) {
    // `-o .` in the folder of the config and its map world.png: the map is
    // the run's input even where an earlier run's manifest lists the name
    const std::string d = freshDir("out");
    writeEarlierOutput(d, {{"world.png", "the user's map"}});
    ASSERT_EQ(fileProblem(d + "/world.png"), "");  // what every reader calls
    // (refused before the work: the commit would replace it, or remove it as
    // the last run's file this run does not write)
    const std::string msg =
        expectBadInputFrom([&] { COutputDir out(d, "risknav-simulate"); });
    EXPECT_NE(msg.find("is an input of this run"), std::string::npos) << msg;
    EXPECT_EQ(readFile(d + "/world.png"), "the user's map");
    // also through a hard link or a symlink of another name
    const std::string inputs = freshDir("inputs");
    writeFile(inputs + "/map.png", "map");
    ASSERT_EQ(fileProblem(inputs + "/map.png"), "");
    const std::string d2 = freshDir("out2");
    writeEarlierOutput(d2, {{"hard.png", "x"}});
    fs::remove(d2 + "/hard.png");
    fs::create_hard_link(inputs + "/map.png", d2 + "/hard.png");
    EXPECT_THROW(COutputDir(d2, "x", {"hard.png"}), CBadInputError);
    EXPECT_TRUE(isRunInput(d2 + "/hard.png"));
    // a folder of the run's that holds an input is not replaced either
    const std::string d3 = freshDir("out3");
    fs::create_directories(d3 + "/snapshots");
    writeFile(d3 + "/snapshots/cycle_1.png", "used as a map");
    writeFile(d3 + "/.risknav-run", "risknav output manifest 2\napp x\ndir snapshots\n");
    ASSERT_EQ(fileProblem(d3 + "/snapshots/cycle_1.png"), "");
    EXPECT_THROW(COutputDir(d3, "x", {"snapshots/"}), CBadInputError);
    EXPECT_EQ(readFile(d3 + "/snapshots/cycle_1.png"), "used as a map");
}

TEST(OutputRules, ARerunReplacesASubfolderWhole) {
    const std::string d = freshDir("out");
    {
        COutputDir out(d, "risknav-explore");
        writeRun(out, "first", 32);
        out.commit();
    }
    EXPECT_EQ(listDir(d + "/snapshots").size(), 32u);
    {
        COutputDir out(d, "risknav-explore");
        writeRun(out, "second", 3);
        out.commit();
    }
    EXPECT_EQ(listDir(d + "/snapshots"),
              (std::vector<std::string>{"cycle_0.png", "cycle_1.png", "cycle_2.png"}));
    EXPECT_EQ(readFile(d + "/snapshots/cycle_2.png"), "png second2");
    EXPECT_EQ(readFile(d + "/.risknav-run"),
              "risknav output manifest 2\napp risknav-explore\nfile summary.json\n"
              "file cycles.csv\ndir snapshots\nfile snapshots/cycle_0.png\n"
              "file snapshots/cycle_1.png\nfile snapshots/cycle_2.png\n");
    // a run without snapshots removes the earlier ones with its commit
    {
        COutputDir out(d, "risknav-explore");
        out.writeText("summary.json", "third");
        out.commit();
    }
    EXPECT_EQ(listDir(d), (std::vector<std::string>{".risknav-run", "summary.json"}));
}

TEST(OutputRules, OnlyAStagingFolderWithItsOwnerMarkerIsRemoved) {
    const std::string d = freshDir("out");
    const std::string elsewhere = freshDir("elsewhere");
    writeFile(elsewhere + "/owner", "risknav staging folder 1\n");
    writeFile(elsewhere + "/precious.txt", "precious");
    // a user's folder of the prefix's name, a symlink to a marked folder, a
    // marked folder with a symlink inside, a wrong marker
    fs::create_directories(d + "/.risknav-stage-users");
    writeFile(d + "/.risknav-stage-users/notes.txt", "user's");
    fs::create_directory_symlink(elsewhere, d + "/.risknav-stage-link");
    fs::create_directories(d + "/.risknav-stage-killed/new");
    writeFile(d + "/.risknav-stage-killed/owner", "risknav staging folder 1\n");
    fs::create_directory_symlink(elsewhere, d + "/.risknav-stage-killed/new/inside");
    fs::create_directories(d + "/.risknav-stage-forged");
    writeFile(d + "/.risknav-stage-forged/owner", "something else\n");
    // an earlier version's temporary names: not recognized by name alone
    fs::create_directories(d + "/.tmp-999999999-navlog");
    { COutputDir out(d); }
    EXPECT_TRUE(fs::exists(d + "/.risknav-stage-users/notes.txt"));
    EXPECT_TRUE(fs::is_symlink(d + "/.risknav-stage-link"));
    EXPECT_FALSE(fs::exists(d + "/.risknav-stage-killed"));
    EXPECT_TRUE(fs::exists(d + "/.risknav-stage-forged/owner"));
    EXPECT_TRUE(fs::exists(d + "/.tmp-999999999-navlog"));
    EXPECT_EQ(readFile(elsewhere + "/precious.txt"), "precious");
    EXPECT_EQ(readFile(elsewhere + "/owner"), "risknav staging folder 1\n");
}

TEST(OutputRules, AKilledRunsScratchIsRemovedByTheNextRun) {
    const std::string d = freshDir("out");
    ASSERT_EQ(inChild([&] {
                  COutputDir out(d, "risknav-navigate");
                  writeRun(out, "killed", 5);
                  ::raise(SIGKILL);
                  return 0;
              }),
              -SIGKILL);
    ASSERT_EQ(listDir(d).size(), 1u);  // the killed run's staging folder
    { COutputDir out(d); }
    EXPECT_TRUE(listDir(d).empty());
}

// Kills a run at each step of its commit in turn (a child process, SIGKILL
// from the commit's step hook), then lets the next run into the folder
// recover: the folder must hold exactly the earlier run's set or exactly the
// killed run's, and the user's file, every time.
TEST(OutputRules, ACommitIsAllOrNothingAcrossAKillAtEveryStep) {
    const std::string d = freshDir("out");
    auto earlier = [&] {
        fs::remove_all(d);
        fs::create_directories(d);
        writeFile(d + "/notes.txt", "the user's own file");
        COutputDir out(d, "risknav-explore");
        writeRun(out, "A", 4);
        out.writeText("only_in_a.csv", "A");
        out.commit();
    };
    earlier();
    const auto setA = tree(d);
    fs::remove_all(d);
    fs::create_directories(d);
    writeFile(d + "/notes.txt", "the user's own file");
    {
        COutputDir out(d, "risknav-explore");
        writeRun(out, "B", 2);
        out.writeText("only_in_b.csv", "B");
        out.commit();
    }
    const auto setB = tree(d);
    int sawA = 0, sawB = 0, steps = 0;
    for (int killAt = 1; killAt < 200; killAt++) {
        earlier();
        const int ended = inChild([&] {
            COutputDir::setCommitStepHook([killAt](int step) {
                if (step == killAt)
                    ::raise(SIGKILL);
            });
            COutputDir out(d, "risknav-explore");
            writeRun(out, "B", 2);
            out.writeText("only_in_b.csv", "B");
            out.commit();
            return 0;
        });
        if (ended != -SIGKILL) {  // no step killAt: every step was covered
            EXPECT_EQ(ended, 0);
            steps = killAt - 1;
            break;
        }
        { COutputDir next(d); }  // completes or rolls back, commits nothing
        const auto now = tree(d);
        if (now == setA)
            sawA++;
        else if (now == setB)
            sawB++;
        else
            ADD_FAILURE() << "a mix of two runs after a kill at step " << killAt;
    }
    EXPECT_GE(steps, 10) << "journal, 2 renames per entry, 1 per dropped entry, end";
    EXPECT_EQ(sawA + sawB, steps);
    EXPECT_EQ(sawA, 2) << "killed before the journal is in place: the earlier set";
    EXPECT_GE(sawB, 8) << "killed after: the next run completes the commit";
}

TEST(OutputRules, AWriteThatFailsNamesTheFileAndTheReason) {
    // A full disk, as the file size limit makes it (EFBIG): one line naming
    // the result's final path and the system's reason.
    const std::string d = freshDir("out");
    EXPECT_EQ(
        inChild([&] {
            limitFileSize(1000);
            COutputDir out(d, "x");
            try {
                out.writeText("summary.json", std::string(5000, 'x'));
            } catch (const std::runtime_error& e) {
                const std::string m = e.what();
                return m == "cannot write " + d + "/summary.json: File too large" ? 0 : 3;
            }
            return 4;
        }),
        0);
    EXPECT_TRUE(listDir(d).empty());
}

TEST(OutputRules, AManifestNameTheRunDidNotWriteIsRefusedNeverReplaced) {
    // a folder, a FIFO (reading it would block) and a file that is no
    // manifest, at the manifest's name
    for (const std::string kind : {"folder", "fifo", "file"}) {
        const std::string d = freshDir(kind);
        if (kind == "folder") {
            fs::create_directories(d + "/.risknav-run");
            writeFile(d + "/.risknav-run/keep.txt", "user's");
        } else if (kind == "fifo") {
            ASSERT_EQ(::mkfifo((d + "/.risknav-run").c_str(), 0644), 0);
        } else {
            writeFile(d + "/.risknav-run", "my notes, not a manifest");
        }
        const auto before = tree(d);
        const std::string msg = expectBadInputFrom([&] { COutputDir out(d, "x"); });
        EXPECT_NE(msg.find("that is not a risknav manifest"), std::string::npos) << msg;
        EXPECT_EQ(tree(d), before) << kind;
    }
}

TEST(OutputRules, AUsersFileInsideTheLastRunsFolderIsNeverRemoved) {
    const std::string d = freshDir("out");
    {
        COutputDir out(d, "risknav-explore");
        writeRun(out, "first", 2);
        out.commit();
    }
    writeFile(d + "/snapshots/my_notes.txt", "the user's");
    const auto before = tree(d);
    // whether this run writes snapshots/ (replaced) or not (removed)
    for (const int snapshots : {2, 0}) {
        const std::string msg = expectBadInputFrom([&] {
            COutputDir out(d, "risknav-explore");
            writeRun(out, "second", snapshots);
            out.commit();
        });
        EXPECT_NE(msg.find("snapshots/my_notes.txt: not written by a risknav run"),
                  std::string::npos)
            << msg;
        EXPECT_EQ(tree(d), before);
    }
}

TEST(OutputRules, AFolderNamedWithATrailingSlashIsTheFolderItself) {
    const std::string target = freshDir("target");
    const std::string link = freshDir("links") + "/out";
    fs::create_directory_symlink(target, link);
    for (const std::string& name : {link + "/", link + "/.", link + "/./"})
        EXPECT_THROW(COutputDir out(name), CBadInputError) << name;
    EXPECT_TRUE(fs::is_empty(target));
    const std::string d = freshDir("real");
    {
        COutputDir out(d + "/./");
        EXPECT_EQ(out.dir(), d);
        out.writeText("summary.json", "{}");
        out.commit();
    }
    EXPECT_EQ(readFile(d + "/summary.json"), "{}");
}

TEST(OutputRules, AFullDiskWhileSettingUpIsARuntimeFailureNotBadInput) {
    const std::string d = freshDir("out");
    EXPECT_EQ(inChild([&] {
                  limitFileSize(0);  // no byte may be written: the owner marker fails
                  try {
                      COutputDir out(d, "x");
                  } catch (const CBadInputError&) {
                      return 3;
                  } catch (const std::runtime_error& e) {
                      return std::string(e.what()).find("File too large") !=
                                     std::string::npos
                                 ? 0
                                 : 5;
                  }
                  return 4;
              }),
              0);
    EXPECT_TRUE(listDir(d).empty());
}
