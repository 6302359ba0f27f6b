// CDeclaredOptions: one declaration per key gives the loader, the saver (with
// comments), the range checks and the documentation list.
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CDeclaredOptions.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::common;

namespace {
struct TDemoOptions : public CDeclaredOptions {
    TDemoOptions() { section = "Demo"; }
    double speed = 0.5;
    int laps = 2;
    bool loop = false;
    double slowest = 0.1;

  protected:
    void declare(Visitor& v) override {
        v.number(speed, "speed", TRange::closed(0, 5, "m/s"), "cruise speed");
        v.integer(laps, "laps", TRange::closed(1, 100), "laps of the route");
        v.flag(loop, "loop", "back to the start after the last lap");
        v.number(slowest, "slowest", TRange::positive("m/s"), "creep speed");
    }
    void validateRules() const override {
        checkRule(slowest <= speed, section, "slowest", numberText(slowest),
                  "must be at most speed");
    }
};

std::string errorOf(const TDemoOptions& o) {
    try {
        o.validate();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "(no error)";
}
}  // namespace

TEST(CDeclaredOptions, LoadsEveryDeclaredKeyAndKeepsDefaultsForTheRest) {
    mrpt::config::CConfigFileMemory c("[Route]\nspeed = 1.5\nloop = true\n");
    TDemoOptions o;
    o.loadFromConfigFile(c, "Route");
    EXPECT_EQ(o.section, "Route");
    EXPECT_DOUBLE_EQ(o.speed, 1.5);
    EXPECT_TRUE(o.loop);
    EXPECT_EQ(o.laps, 2);
}

TEST(CDeclaredOptions, ChecksEachDeclaredRangeThenTheRules) {
    TDemoOptions o;
    EXPECT_EQ(errorOf(o), "(no error)");
    o.laps = 0;
    EXPECT_NE(errorOf(o).find("[Demo] laps = '0': must be in [1, 100]"),
              std::string::npos)
        << errorOf(o);
    o.laps = 3;
    o.speed = 6;
    EXPECT_NE(errorOf(o).find("[Demo] speed"), std::string::npos);
    o.speed = 0.05;  // in range, but below the creep speed
    EXPECT_NE(errorOf(o).find("[Demo] slowest"), std::string::npos) << errorOf(o);
}

TEST(CDeclaredOptions, SavesWithTheDocAndRangeAsCommentsAndLoadsBack) {
    TDemoOptions o;
    o.speed = 0.75;
    o.laps = 7;
    mrpt::config::CConfigFileMemory c;
    o.saveToConfigFile(c, "Demo");
    const std::string text = c.getContent();
    EXPECT_NE(text.find("cruise speed, [0, 5] m/s"), std::string::npos) << text;
    EXPECT_NE(text.find("laps of the route, [1, 100]"), std::string::npos) << text;
    EXPECT_NE(text.find("true | false"), std::string::npos) << text;
    // the comment is a comment: the text loads back to the same values
    mrpt::config::CConfigFileMemory back(text);
    TDemoOptions p;
    p.loadFromConfigFile(back, "Demo");
    EXPECT_DOUBLE_EQ(p.speed, 0.75);
    EXPECT_EQ(p.laps, 7);
    EXPECT_FALSE(p.loop);
}

TEST(CDeclaredOptions, ListsEveryKeyWithItsDocRangeAndValue) {
    const auto keys = TDemoOptions().keys();
    ASSERT_EQ(keys.size(), 4u);
    EXPECT_EQ(keys[0].key, "speed");
    EXPECT_EQ(keys[0].doc, "cruise speed");
    EXPECT_EQ(keys[0].range, "[0, 5] m/s");
    EXPECT_EQ(keys[0].defaultText, "0.5");
    EXPECT_EQ(keys[2].range, "true | false");
}

namespace {
struct TKindsOptions : public CDeclaredOptions {
    TKindsOptions() { section = "Kinds"; }
    std::string label = "LASER";
    std::string file;
    double fov = M_PI;  // [rad]

  protected:
    void declare(Visitor& v) override {
        v.text(label, "label", true, "the sensor's label");
        v.path(file, "file", true, "a map file ('' = none)");
        v.degrees(fov, "fov_deg", TRange::closed(1, 360, "deg"), "field of view");
    }
};
}  // namespace

// Text, paths and angles: degrees in the file, radians in the struct; an
// empty label refused; a given path that is not there refused, none allowed.
TEST(CDeclaredOptions, TextPathsAndDegrees) {
    TKindsOptions o;
    mrpt::config::CConfigFileMemory c("[Kinds]\nlabel = FRONT\nfov_deg = 90\n");
    o.loadFromConfigFile(c, "Kinds");
    EXPECT_EQ(o.label, "FRONT");
    EXPECT_NEAR(o.fov, M_PI / 2, 1e-12);
    EXPECT_EQ(o.file, "");
    o.validate();
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "Kinds");
    EXPECT_NE(saved.getContent().find("field of view, [1, 360] deg"), std::string::npos)
        << saved.getContent();
    // (as text: MRPT keeps a padded name in memory)
    const mrpt::config::CConfigFileMemory text(saved.getContent());
    EXPECT_EQ(text.read_string("Kinds", "fov_deg", ""), "90");
    const auto keys = o.keys();
    ASSERT_EQ(keys.size(), 3u);
    EXPECT_EQ(keys[2].defaultText, "90");
    EXPECT_EQ(keys[1].range, "a file path");

    o.fov = 2 * M_PI + 0.1;
    EXPECT_THROW(o.validate(), std::exception);
    o.fov = 1;
    o.label = "";
    EXPECT_THROW(o.validate(), std::exception);

    mrpt::config::CConfigFileMemory missing("[Kinds]\nfile = /nonexistent/map.png\n");
    TKindsOptions p;
    EXPECT_THROW(p.loadFromConfigFile(missing, "Kinds"), CBadInputError);
}

// What is saved loads back from the same in-memory config, without
// reparsing its text (a library user's round trip), and reads as
// "key = value // doc, range".
TEST(CDeclaredOptions, ARoundTripInMemoryKeepsTheValues) {
    TDemoOptions o;
    o.speed = 1.25;
    o.laps = 9;
    o.loop = true;
    mrpt::config::CConfigFileMemory c;
    o.saveToConfigFile(c, "Demo");
    TDemoOptions p;
    p.loadFromConfigFile(c, "Demo");
    EXPECT_DOUBLE_EQ(p.speed, 1.25);
    EXPECT_EQ(p.laps, 9);
    EXPECT_TRUE(p.loop);
    EXPECT_NE(c.getContent().find("laps = 9 // laps of the route, [1, 100]"),
              std::string::npos)
        << c.getContent();
}
