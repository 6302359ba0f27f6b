#include <risknav/common/CAppRunner.h>
#include <risknav/common/CBadInputError.h>

#include <gtest/gtest.h>

#include "test_support.h"

using namespace risknav::common;

namespace {
const TAppInfo kInfo{"risknav-demo", "A demo app.", ""};
const TAppInfo kInfoExtra{"risknav-demo", "A demo app.", "[RAWLOG ...]"};

TAppArgs parse(std::vector<std::string> a, const TAppInfo& i = kInfo) {
    return parseAppArgs(a, i);
}

int runWith(std::vector<std::string> args,
            const std::function<void(const TAppContext&)>& body) {
    args.insert(args.begin(), "risknav-demo");
    std::vector<char*> argv;
    for (auto& s : args)
        argv.push_back(s.data());
    return runApp(int(argv.size()), argv.data(), kInfo, body);
}
}  // namespace

TEST(CommandLine, DefaultsAndAllOptions) {
    auto a = parse({"w.ini"});
    EXPECT_EQ(a.configPath, "w.ini");
    EXPECT_EQ(a.outDir, "out/demo");
    EXPECT_FALSE(a.quiet);
    EXPECT_FALSE(a.seed.has_value());
    a = parse(
        {"-q", "--out", "o", "--set", "A.b=1", "--set=C.d=2", "--seed", "42", "w.ini"});
    EXPECT_TRUE(a.quiet);
    EXPECT_EQ(a.outDir, "o");
    EXPECT_EQ(a.sets, (std::vector<std::string>{"A.b=1", "C.d=2"}));
    EXPECT_EQ(*a.seed, 42u);
    EXPECT_EQ(parse({"-o", "x", "w.ini"}).outDir, "x");
    EXPECT_EQ(parse({"--out=y", "--seed=0", "w.ini"}).outDir, "y");
    EXPECT_TRUE(parse({"--help"}).help);
    EXPECT_TRUE(parse({"-h"}).help);
    EXPECT_TRUE(parse({"--version"}).version);
    EXPECT_EQ(parse({"w.ini", "a.rawlog", "b.rawlog"}, kInfoExtra).extra.size(), 2u);
}

TEST(CommandLine, UsageErrorsAreBadInput) {
    EXPECT_THROW(parse({}), CBadInputError);
    EXPECT_THROW(parse({"--bogus", "w.ini"}), CBadInputError);
    EXPECT_THROW(parse({"--out"}), CBadInputError);
    // an empty value would otherwise take the next option as the folder
    EXPECT_THROW(parse({"w.ini", "--out", "", "-q"}), CBadInputError);
    EXPECT_THROW(parse({"w.ini", "--out="}), CBadInputError);
    EXPECT_THROW(parse({"w.ini", "-o", ""}), CBadInputError);
    EXPECT_THROW(parse({"--seed", "-3", "w.ini"}), CBadInputError);
    EXPECT_THROW(parse({"--seed", "12x", "w.ini"}), CBadInputError);
    // a line break would cut every one-line message naming the path
    EXPECT_THROW(parse({"--out", "a\nb", "w.ini"}), CBadInputError);
    EXPECT_THROW(parse({"w\n.ini"}), CBadInputError);
    // given twice, the last would silently win
    EXPECT_THROW(parse({"-o", "a", "--out=b", "w.ini"}), CBadInputError);
    EXPECT_THROW(parse({"--seed", "1", "--seed=2", "w.ini"}), CBadInputError);
    EXPECT_THROW(parse({"w.ini", "extra"}),
                 CBadInputError);  // this app takes no extra args
}

TEST(CommandLine, HelpMentionsEveryOption) {
    const std::string h = appUsage(kInfo);
    for (const char* opt :
         {"--out", "--set", "--quiet", "--seed", "--help", "--version", "exit status"})
        EXPECT_NE(h.find(opt), std::string::npos) << opt;
    EXPECT_NE(versionString(kInfo).find("MRPT 2.5"), std::string::npos);
}

TEST(RunApp, ExitCodes) {
    const std::string ini = risknav::test::freshDir("cli") + "/a.ini";
    risknav::test::writeFile(ini, "[S]\nk = 1\n");
    EXPECT_EQ(runWith({"--help"}, [](const TAppContext&) { FAIL(); }), 0);
    EXPECT_EQ(runWith({ini}, [](const TAppContext&) {}), 0);
    EXPECT_EQ(runWith({"/no/such.ini"}, [](const TAppContext&) { FAIL(); }), 2);
    EXPECT_EQ(runWith({"--nope", ini}, [](const TAppContext&) { FAIL(); }), 2);
    EXPECT_EQ(runWith({ini}, [](const TAppContext&) { throw CBadInputError("bad"); }), 2);
    EXPECT_EQ(
        runWith({ini}, [](const TAppContext&) { throw std::runtime_error("boom"); }), 1);
    // --set reaches the config the body sees.
    double seen = 0;
    EXPECT_EQ(
        runWith({"--set", "S.k=7", ini},
                [&](const TAppContext& c) { seen = c.cfg.read_double("S", "k", 0); }),
        0);
    EXPECT_DOUBLE_EQ(seen, 7.0);
}

TEST(RunApp, FirstLineOnly) {
    EXPECT_EQ(firstLine("\n  first\nsecond\n"), "first");
    EXPECT_EQ(firstLine(""), "unknown error");
    EXPECT_EQ(firstLine("==== MRPT exception ====\nMessage:  Undefined symbol "
                        "'x'\nLocation: a.cpp:1\n"),
              "Undefined symbol 'x'");
    // after a prefix, and MRPT's config parser's form without "Message:"
    EXPECT_EQ(firstLine("a.ini: cannot parse config file: ==== MRPT exception ====\n"
                        "Line 2: Unknown variable `${U}`\nCall stack backtrace:\n"),
              "a.ini: cannot parse config file: Line 2: Unknown variable `${U}`");
    // a binary file quoted: control bytes and bytes that are not UTF-8 become '?'
    EXPECT_EQ(firstLine(std::string("line 1: 'a\x01\x17\tb\xff\xc3\xa9'", 18)),
              "line 1: 'a?? b?\xc3\xa9'");
}
