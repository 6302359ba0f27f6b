#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/config_read.h>

#include <gtest/gtest.h>

#include <filesystem>

#include <sys/stat.h>

#include "test_support.h"

using namespace risknav::common;
using risknav::test::freshDir;
using risknav::test::writeFile;

namespace {
// A config file on disk (CIniConfig needs a real file: it knows its folder).
std::string iniFile(const std::string& content, const std::string& name = "test.ini") {
    const std::string path = freshDir("cfg") + "/" + name;
    writeFile(path, content);
    return path;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const CBadInputError& e) {
        return e.what();
    }
    return "(no error)";
}
}  // namespace

TEST(TRange, ContainsAndDescribes) {
    EXPECT_TRUE(TRange::positive().contains(1e-9));
    EXPECT_FALSE(TRange::positive().contains(0.0));
    EXPECT_TRUE(TRange::nonNegative().contains(0.0));
    EXPECT_FALSE(TRange::closed(0, 1).contains(1.0001));
    EXPECT_FALSE(TRange::any().contains(std::nan("")));
    EXPECT_EQ(TRange::positive("m/s").describe(), "must be in (0, inf) m/s");
    EXPECT_EQ(TRange::closed(0.5, 2).describe(), "must be in [0.5, 2]");
}

TEST(ConfigRead, StrictNumbersWithFullErrorMessages) {
    const std::string p = iniFile(
        "[Robot]\nmax_v = 0.8\nbad = 0.5 ; not an MRPT comment\nneg = -1\nword = fast\n"
        "res = 0\n");
    CIniConfig c(p);
    EXPECT_DOUBLE_EQ(readDouble(c, "Robot", "max_v", 0.0, TRange::positive("m/s")), 0.8);
    EXPECT_DOUBLE_EQ(readDouble(c, "Robot", "missing", 1.5, TRange::positive("m/s")),
                     1.5);
    // Trailing garbage is an error, not a silent 0.5 or an uncaught std::stod throw.
    const std::string e1 =
        errorOf([&] { readDouble(c, "Robot", "bad", 0, TRange::any()); });
    EXPECT_NE(e1.find(p), std::string::npos) << e1;
    EXPECT_NE(e1.find("[Robot] bad = '0.5 ; not an MRPT comment': not a number"),
              std::string::npos)
        << e1;
    const std::string e2 =
        errorOf([&] { readDouble(c, "Robot", "neg", 0, TRange::positive("m/s")); });
    EXPECT_EQ(e2, p + ": [Robot] neg = '-1': must be in (0, inf) m/s");
    const std::string e3 = errorOf(
        [&] { readDouble(c, "Robot", "res", 0, TRange::closed(0.001, 10, "m")); });
    EXPECT_EQ(e3, p + ": [Robot] res = '0': must be in [0.001, 10] m");
    EXPECT_NE(errorOf([&] {
                  readDouble(c, "Robot", "word", 0, TRange::any());
              }).find("not a number"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  requireDouble(c, "Robot", "absent", TRange::positive());
              }).find("[Robot] absent: required key is missing"),
              std::string::npos);
}

TEST(ConfigRead, OnlyDecimalNumbersThatDoNotUnderflow) {
    // strtod alone takes hex and silently rounds 1e-400 to 0 (both seen in
    // risknav-explore's configs)
    const std::string p = iniFile(
        "[A]\nhex = 0x10\nhexf = 0x1.8p1\ntiny = 1e-400\nsub = 1e-310\ninf = inf\n"
        "nan = nan\nok = -1.5e-3\nbig = 1e400\n");
    CIniConfig c(p);
    for (const char* k : {"hex", "hexf", "tiny", "sub", "inf", "nan", "big"}) {
        const std::string e = errorOf([&] { readDouble(c, "A", k, 0, TRange::any()); });
        EXPECT_NE(e.find("not a number"), std::string::npos) << k << ": " << e;
    }
    EXPECT_DOUBLE_EQ(readDouble(c, "A", "ok", 0, TRange::any()), -1.5e-3);
    EXPECT_NE(errorOf([&] {
                  readInt(c, "A", "hex", 0, TRange::any());
              }).find("'0x10': not an integer"),
              std::string::npos);
}

TEST(ConfigRead, IntsBoolsChoicesLists) {
    CIniConfig c(
        iniFile("[A]\nn = 3\nf = 2.5\nb = yes\nbb = maybe\nmode = loop\nv = [1, 2 3 "
                "4]\nodd = 1 2 3\n"));
    EXPECT_EQ(readInt(c, "A", "n", 0, TRange::closed(1, 10)), 3);
    EXPECT_NE(
        errorOf([&] { readInt(c, "A", "f", 0, TRange::any()); }).find("not an integer"),
        std::string::npos);
    EXPECT_TRUE(readBool(c, "A", "b", false));
    EXPECT_NE(
        errorOf([&] { readBool(c, "A", "bb", false); }).find("must be true or false"),
        std::string::npos);
    EXPECT_EQ(readChoice(c, "A", "mode", "once", {"once", "loop"}), "loop");
    EXPECT_NE(errorOf([&] {
                  readChoice(c, "A", "mode", "once", {"once", "back_and_forth"});
              }).find("must be one of: once, back_and_forth"),
              std::string::npos);
    EXPECT_EQ(readNumbers(c, "A", "v", {}, TRange::any()),
              (std::vector<double>{1, 2, 3, 4}));
    EXPECT_NE(errorOf([&] {
                  readNumbers(c, "A", "odd", {}, TRange::any(), 0, 2);
              }).find("multiple of 2"),
              std::string::npos);
}

TEST(ConfigRead, MrptPreprocessorWorks) {
    CIniConfig c(
        iniFile("@define SPEED 0.4\n[R]\nv = ${SPEED}  // m/s\nw = $eval{2*SPEED}\n"));
    EXPECT_DOUBLE_EQ(readDouble(c, "R", "v", 0, TRange::any()), 0.4);
    EXPECT_DOUBLE_EQ(readDouble(c, "R", "w", 0, TRange::any()), 0.8);
}

TEST(CIniConfig, PreprocessorErrorsAreOneLineBadInput) {
    const std::string e =
        errorOf([] { CIniConfig c(iniFile("[A]\nk = $eval{nosuchvar+1}\n")); });
    EXPECT_NE(e.find("cannot parse config file"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(ConfigRead, PathsResolveAgainstTheConfigFolder) {
    const std::string p = iniFile("[W]\nmap_file = maps/m.png\nabs = /etc/hostname\n");
    const std::string dir = std::filesystem::path(p).parent_path().string();
    CIniConfig c(p);
    EXPECT_EQ(readPath(c, "W", "map_file", "", false), dir + "/maps/m.png");
    EXPECT_NE(
        errorOf([&] { readPath(c, "W", "map_file", "", true); }).find("file not found"),
        std::string::npos);
    std::filesystem::create_directories(dir + "/maps");
    writeFile(dir + "/maps/m.png", "x");
    EXPECT_EQ(readPath(c, "W", "map_file", "", true), dir + "/maps/m.png");
    EXPECT_EQ(readPath(c, "W", "abs", "", false), "/etc/hostname");
}

TEST(CIniConfig, MissingOrUnreadableFileIsBadInput) {
    EXPECT_NE(
        errorOf([] { CIniConfig c("/nonexistent/x.ini"); }).find("config file not found"),
        std::string::npos);
    const std::string dir = freshDir("d");
    EXPECT_NE(errorOf([&] { CIniConfig c(dir); }).find("config file is a folder"),
              std::string::npos);
    // a device would never end (was "not found" in the other readers)
    EXPECT_EQ(errorOf([&] { CIniConfig c("/dev/zero"); }),
              "/dev/zero: config file is not a regular file (a device, FIFO or socket)");
}

TEST(ConfigRead, FileProblemTellsMissingFolderAndDevice) {
    const std::string dir = freshDir("fp");
    writeFile(dir + "/f", "x");
    std::filesystem::create_symlink(dir + "/f", dir + "/link");
    EXPECT_EQ(fileProblem(dir + "/f"), "");
    EXPECT_EQ(fileProblem(dir + "/link"), "");
    EXPECT_EQ(fileProblem(dir + "/none"), "not found");
    EXPECT_EQ(fileProblem(dir), "is a folder, not a file");
    EXPECT_EQ(fileProblem("/dev/null"),
              "is not a regular file (a device, FIFO or socket)");
    ASSERT_EQ(::mkfifo((dir + "/fifo").c_str(), 0600), 0);
    EXPECT_EQ(fileProblem(dir + "/fifo"),
              "is not a regular file (a device, FIFO or socket)");
}

TEST(CIniConfig, ANulByteIsAnErrorNotTheEndOfTheFile) {
    // MRPT's reader ends the text at the NUL: [B] was silently gone
    const std::string path =
        iniFile(std::string("[A]\nx = 1\n") + std::string(1, '\0') + "\n[B]\ny = 2\n");
    EXPECT_EQ(errorOf([&] { CIniConfig c(path); }),
              path +
                  ": line 3: a NUL byte (a binary file? MRPT's reader would drop "
                  "everything after it)");
}

TEST(ConfigRead, LongValuesAndLinesAreQuotedClipped) {
    EXPECT_EQ(clippedText("abc", 3), "abc");
    EXPECT_EQ(clippedText("abcd", 3), "abc... (4 bytes)");
    const std::string big(1000000, '9');
    CIniConfig c(iniFile("[A]\nv = " + big + "\n"));
    const std::string e = errorOf([&] { readDouble(c, "A", "v", 0, TRange::any()); });
    EXPECT_LT(e.size(), 400u);
    EXPECT_NE(e.find("... (1000000 bytes)': not a number"), std::string::npos);
    const std::string line = iniFile("[A]\n" + std::string(1000000, 'x') + "\n");
    EXPECT_LT(errorOf([&] { CIniConfig bad(line); }).size(), 400u);
}

TEST(CIniConfig, ReportsKeysNobodyRead) {
    CIniConfig c(iniFile("[Robot]\nmax_v = 1\nmax_vv = 2\n[Other]\nk = 1\n"));
    readDouble(c, "Robot", "max_v", 0, TRange::any());
    // MRPT's own macros go through the same tracked readString().
    double k = 0;
    MRPT_LOAD_HERE_CONFIG_VAR(k, double, k, c, "Other");
    EXPECT_EQ(c.unreadKeys(), (std::vector<std::string>{"[Robot] max_vv"}));
    const std::string e = errorOf([&] { c.throwOnUnreadKeys(); });
    EXPECT_NE(e.find("unknown key [Robot] max_vv"), std::string::npos) << e;
}

TEST(CIniConfig, HasKeyIgnoresKeyCaseAndSeesKeysWrittenLater) {
    CIniConfig c(iniFile("[Robot]\nmax_v = 1\n[Other]\nk = 1\n"));
    EXPECT_TRUE(c.hasKey("Robot", "max_v"));
    EXPECT_TRUE(c.hasKey("Robot", "MAX_V"));
    EXPECT_FALSE(c.hasKey("Robot", "k"));
    EXPECT_FALSE(c.hasKey("Nowhere", "k"));
    // hasKey() lists a section's keys once; a write (--set, the apps' own
    // writes) must not leave that list stale
    c.write("Robot", "radius", 0.3);
    c.write("Nowhere", "k", 1);
    EXPECT_TRUE(c.hasKey("Robot", "radius"));
    EXPECT_TRUE(c.hasKey("Nowhere", "k"));
    EXPECT_TRUE(c.hasKey("Robot", "max_v"));
}

TEST(CIniConfig, OverridesNeverTouchTheFileOnDisk) {
    const std::string text = "[Route]\nspeed = 0.2 // m/s\n\n\n[Other]\nk=1\n";
    const std::string p = iniFile(text);
    {
        CIniConfig c(p);
        c.applyOverride("Route.speed=0.9");
        c.applyOverride("New.key=1");
        EXPECT_DOUBLE_EQ(readDouble(c, "Route", "speed", 0, TRange::any()), 0.9);
    }
    EXPECT_EQ(risknav::test::readFile(p), text);
}

TEST(CIniConfig, OverridesFromTheCommandLine) {
    CIniConfig c(iniFile("[Route]\nspeed = 0.2\n"));
    c.applyOverride("Route.speed=0.5");
    c.applyOverride("Route.laps=4");  // a key not in the file is fine if code reads it
    EXPECT_DOUBLE_EQ(readDouble(c, "Route", "speed", 0, TRange::any()), 0.5);
    EXPECT_EQ(readInt(c, "Route", "laps", 1, TRange::any()), 4);
    c.applyOverride("Route.lapz=4");  // a typo is caught as an unknown key
    EXPECT_EQ(c.unreadKeys(), (std::vector<std::string>{"[Route] lapz"}));
    EXPECT_EQ(
        errorOf([&] { c.throwOnUnreadKeys(); }),
        c.path() +
            " (--set): unknown key [Route] lapz; see config/ for the documented keys");
    EXPECT_NE(errorOf([&] {
                  c.applyOverride("Route_speed=1");
              }).find("expected SECTION.KEY=VALUE"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                  c.applyOverride("Route.speed");
              }).find("expected SECTION.KEY=VALUE"),
              std::string::npos);
    // a line break would cut the one-line message (the file cannot hold one)
    EXPECT_EQ(errorOf([&] { c.applyOverride("Route.speed=1\nrest"); }),
              "--set 'Route.speed=1...': a line break or NUL byte in the value");
    // a bad value from --set is said to come from --set, not from the file
    c.applyOverride("route.SPEED=fast");
    EXPECT_EQ(errorOf([&] { readDouble(c, "Route", "speed", 0, TRange::any()); }),
              c.path() + " (--set): [Route] speed = 'fast': not a number");
}

TEST(CIniConfig, AnUnknownSectionSaysWhetherOnlyTheCommandLineGaveIt) {
    CIniConfig c(iniFile("[Route]\nspeed = 0.2\n[Routes]\nk = 1\n"));
    EXPECT_EQ(errorOf([&] { c.throwUnknownSection("Routes", "Route"); }),
              c.path() + ": unknown section [Routes] (known: Route)");
    c.applyOverride("Rout.speed=1");
    EXPECT_EQ(errorOf([&] { c.throwUnknownSection("Rout", "Route"); }),
              c.path() + " (--set): unknown section [Rout] (known: Route)");
    // a section the file has, given one more key by --set, is the file's
    c.applyOverride("Routes.j=1");
    EXPECT_EQ(errorOf([&] { c.throwUnknownSection("Routes", "Route"); }),
              c.path() + ": unknown section [Routes] (known: Route)");
}

TEST(CIniConfig, AnOldNameIsRefusedWithItsNewName) {
    // the same thing has one name in every app; the old one is never read
    const std::string a = iniFile("[Explore]\nTime_Limit = 20\n");
    EXPECT_EQ(errorOf([&] { CIniConfig c(a); }),
              a + ": [Explore] Time_Limit is now [Explore] duration_max");
    const std::string b = iniFile("[stoppingrule]\nmargin = 0.1\n");
    EXPECT_EQ(errorOf([&] { CIniConfig c(b); }),
              b + ": section [stoppingrule] is now [CStoppingDistanceLimiter]");
    const std::string v = iniFile("[ViewpointPlan]\nstart = 1 2\n");
    CIniConfig c(v);
    EXPECT_EQ(errorOf([&] { c.applyOverride("ViewpointPlan.goal_y=3"); }),
              v + " (--set): [ViewpointPlan] goal_y is now [ViewpointPlan] goal = x y");
    // the same key in a section where it was never renamed is fine
    EXPECT_EQ(errorOf([&] { CIniConfig d(iniFile("[Simulation]\ntime_limit = 3\n")); }),
              "(no error)");
}

TEST(ConfigRead, LongSectionAndKeyNamesAreClippedInMessages) {
    const std::string longKey(5000, 'k');
    CIniConfig c(iniFile("[Route]\n" + longKey + " = abc\n"));
    const std::string e =
        errorOf([&] { readDouble(c, "Route", longKey, 0, TRange::any()); });
    EXPECT_LT(e.size(), 400u) << e;
    EXPECT_NE(e.find("(5000 bytes)"), std::string::npos) << e;
    EXPECT_NE(e.find("not a number"), std::string::npos) << e;
}

namespace {
struct TDemoOptions {
    double a = 1, b = 2;
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                            const std::string& s) {
        a = readDouble(c, s, "a", a, TRange::any());
        b = readDouble(c, s, "b", b, TRange::any());
    }
    void validate() const {
        if (b < a)
            throw CConfigKeyError("Demo", "b", std::to_string(b), "must be >= a");
    }
};
}  // namespace

TEST(ConfigRead, LoadOptionsAddsTheFileToValidateErrors) {
    const std::string p = iniFile("[Demo]\na = 3\nb = 2\n");
    CIniConfig c(p);
    TDemoOptions o;
    const std::string e = errorOf([&] { loadOptions(o, c, "Demo"); });
    EXPECT_EQ(e, p + ": [Demo] b = '2.000000': must be >= a");
}

TEST(CIniConfig, DuplicateKeysAndLinesWithoutEqualsAreErrors) {
    auto expectLine = [](const std::string& text, const std::string& what) {
        const std::string f = iniFile(text);
        try {
            CIniConfig c(f);
            FAIL() << "accepted: " << text;
        } catch (const CBadInputError& e) {
            const std::string m = e.what();
            EXPECT_EQ(m.rfind(f + ": line ", 0), 0u) << m;
            EXPECT_NE(m.find(what), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    };
    // MRPT would keep the last value / drop the line silently.
    expectLine("[Robot]\nradius = 0.25\nRadius = 0.3\n",
               "line 3: [Robot] Radius is given twice (also line 2)");
    expectLine("[Robot]\nmax_v    1.1\n",
               "line 2: 'max_v    1.1' in [Robot]: expected KEY = VALUE");
    expectLine("[Robot\nradius = 1\n", "a section needs a closing ']'");
    // The same key in two sections, comments, preprocessor lines and line
    // continuations are fine.
    EXPECT_NO_THROW(
        CIniConfig(iniFile("; c\n# c\n// c\n@define R 0.25\n[A]\nk = ${R}\n"
                           "l = 1 \\\n  2\n[B]\nk = 2\n")));
}

TEST(ConfigRead, CopyConfigKeysCopiesAllButTheSkipped) {
    mrpt::config::CConfigFileMemory from, to;
    from.write("A", "x", 1);
    from.write("A", "y", "two");
    from.write("B", "z", 3.5);
    to.write("A", "x", 0);
    copyConfigKeys(from, to, [](const std::string& s, const std::string& k) {
        return s == "A" && k == "y";
    });
    EXPECT_EQ(to.read_int("A", "x", -1), 1);  // overwritten
    EXPECT_FALSE(to.keyExists("A", "y"));
    EXPECT_DOUBLE_EQ(to.read_double("B", "z", 0), 3.5);
    copyConfigKeys(from, to);
    EXPECT_EQ(to.read_string("A", "y", ""), "two");
}

TEST(ConfigRead, AValueErrorFromValidateQuotesTheValueAsTyped) {
    // validate() sees the parsed number; the message quotes the file's text
    // when it is that one number ('1e9', not '1e+09')
    struct TOpts {
        double v = 0;
        std::vector<double> list;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s) {
            v = readDouble(c, s, "v", v);
            list = readNumbers(c, s, "list", {1.0});
        }
        void validate() const {
            checkKey("S", "v", v, TRange::closed(0, 100));
            checkKey("S", "list", list, TRange::closed(0, 100));
        }
    };
    const std::string p = iniFile("[S]\nv = 1e9\nlist = 1 2e3\n");
    CIniConfig c(p);
    TOpts o;
    EXPECT_EQ(errorOf([&] { loadOptions(o, c, "S"); }),
              p + ": [S] v = '1e9': must be in [0, 100]");
    CIniConfig c2(iniFile("[S]\nv = 5\nlist = 1 2e3\n"));
    const std::string e = errorOf([&] { loadOptions(o, c2, "S"); });
    EXPECT_EQ(e, c2.path() + ": [S] list = '1 2e3': '2e3' must be in [0, 100]");
    // text that is not the same numbers (a rule on a derived value) stays
    EXPECT_EQ(typedValueMessage(c2, CConfigKeyError("S", "v", "6", "rule")),
              "[S] v = '6': rule");
}
