// The config text as MRPT reads it: duplicate keys are found after MRPT's own
// preprocessing and line splitting, and config_effective.ini loads back.
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/config_read.h>

#include <gtest/gtest.h>

#include <filesystem>

#include "test_support.h"

using namespace risknav::common;
using risknav::test::freshDir;
using risknav::test::writeFile;

namespace {
std::string iniIn(const std::string& dir, const std::string& content) {
    std::filesystem::create_directories(dir);
    const std::string path = dir + "/test.ini";
    writeFile(path, content);
    return path;
}

std::string errorOf(const std::string& path) {
    try {
        CIniConfig c(path);
    } catch (const CBadInputError& e) {
        return e.what();
    }
    return "(no error)";
}
}  // namespace

// SimpleIni splits lines at a lone CR as well: a CR-only file (classic Mac
// OS) was one line to the check, and its duplicate went through.
TEST(CIniConfigText, DuplicateKeysInCrOnlyAndMixedLineEndings) {
    const std::string dir = freshDir("crdup");
    const std::string cr = iniIn(dir + "/cr", "[Robot]\rradius = 0.25\rradius = 0.3\r");
    EXPECT_EQ(errorOf(cr), cr + ": line 3: [Robot] radius is given twice (also line 2)");
    const std::string mixed =
        iniIn(dir + "/mixed", "[Robot]\r\nmax_v = 1\rradius = 0.25\nRADIUS = 0.3\r\n");
    EXPECT_EQ(errorOf(mixed),
              mixed + ": line 4: [Robot] RADIUS is given twice (also line 3)");
    // a line without '=' hidden behind a CR
    const std::string noEq = iniIn(dir + "/noeq", "[Robot]\rradius 0.25\r");
    EXPECT_NE(
        errorOf(noEq).find(": line 2: 'radius 0.25' in [Robot]: expected KEY = VALUE"),
        std::string::npos)
        << errorOf(noEq);
    // and a clean CR-only file reads as MRPT reads it
    CIniConfig ok(iniIn(dir + "/ok", "[Robot]\rradius = 0.25\rmax_v = 1\r"));
    EXPECT_DOUBLE_EQ(readDouble(ok, "Robot", "max_v", 0), 1.0);
}

// Section and key names made by MRPT's preprocessor are the names MRPT keeps.
TEST(CIniConfigText, DuplicatesThroughDefinedNames) {
    const std::string dir = freshDir("defdup");
    const std::string sec = iniIn(dir + "/sec",
                                  "@define SEC Robot\n[${SEC}]\nradius = 0.25\n"
                                  "[Robot]\nradius = 0.3\n");
    EXPECT_EQ(errorOf(sec),
              sec + ": line 5: [Robot] radius is given twice (also line 3)");
    const std::string key =
        iniIn(dir + "/key", "@define K radius\n[Robot]\n${K} = 0.25\nradius = 0.3\n");
    EXPECT_EQ(errorOf(key),
              key + ": line 4: [Robot] radius is given twice (also line 3)");
    const std::string ev = iniIn(dir + "/eval",
                                 "@define N 2\n[Route${N}]\nname = a\n[Route2]\n"
                                 "name = b\n");
    EXPECT_NE(errorOf(ev).find("[Route2] name is given twice"), std::string::npos)
        << errorOf(ev);
    // a line continuation joins lines as MRPT does: line numbers stay those of
    // the file
    const std::string cont = iniIn(dir + "/cont", "[A]\nk = 1 \\\n  2\nl = 3\r\nk = 4\n");
    EXPECT_EQ(errorOf(cont), cont + ": line 5: [A] k is given twice (also line 2)");
    // distinct names stay fine
    EXPECT_EQ(errorOf(iniIn(dir + "/fine",
                            "@define K radius\n[Robot]\n${K} = 0.25\nmax_v = 1\n")),
              "(no error)");
}

// config_effective.ini names the source config and holds resolved paths: a
// folder named with MRPT's preprocessor syntax must still load back.
TEST(CIniConfigText, EffectiveConfigWithPreprocessorTextLoadsBack) {
    const std::string dir =
        freshDir("eff") + "/run ${HOME} $eval{1+1} $env{PATH} @define X";
    std::filesystem::create_directories(dir);
    mrpt::config::CConfigFileMemory saved;
    const std::string map = dir + "/map.png";
    writeKey(saved, "World", "map_file", map);
    writeKey(saved, "World", "note", std::string("a $ b @ c ${ d"));
    writeKey(saved, "Robot", "radius", 0.25);
    const std::string text = effectiveConfigText(dir + "/source.ini", saved);
    const std::string path = dir + "/config_effective.ini";
    writeFile(path, text);
    CIniConfig back(path);
    EXPECT_EQ(readString(back, "World", "map_file", ""), map);
    EXPECT_EQ(readString(back, "World", "note", ""), "a $ b @ c ${ d");
    EXPECT_DOUBLE_EQ(readDouble(back, "Robot", "radius", 0), 0.25);
    EXPECT_TRUE(back.unreadKeys().empty());
    // without such text, the file is as before (no defines)
    mrpt::config::CConfigFileMemory plain;
    writeKey(plain, "Robot", "radius", 0.25);
    EXPECT_EQ(effectiveConfigText("/cfg/a.ini", plain).find("@define"),
              std::string::npos);
}
