// CDeclaredOptions: one declaration per key gives the loader, the saver (with
// comments), the range checks and the documentation list.
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CDeclaredOptions.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

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

namespace {
struct TSubOptions : public CDeclaredOptions {
    TSubOptions() { section = "Sub"; }
    double width = 1;
    double height = 1;

  protected:
    void declare(Visitor& v) override {
        v.number(width, "width", TRange::closed(0, 10, "m"), "width");
        v.number(height, "height", TRange::closed(0, 10, "m"), "height");
    }
    void validateRules() const override {
        checkRule(height <= width, section, "height", numberText(height),
                  "must be at most width");
    }
};
struct TShapeOptions : public CDeclaredOptions {
    TShapeOptions() { section = "Shape"; }
    std::string name;
    mrpt::math::TPoint2D centre{std::nan(""), std::nan("")};
    std::vector<mrpt::math::TPoint2D> outline;
    double x = 0;
    std::optional<double> heading_deg;
    std::vector<double> corners = {0, 0, 1, 1};
    TSubOptions size;

  protected:
    void declare(Visitor& v) override {
        v.text(name, "name", false, "defaults to the section's name");
        v.point(centre, "centre", TRange::closed(-100, 100, "m"), "x y");
        v.points(outline, "outline", TRange::closed(-100, 100, "m"), "x y pairs",
                 TCount{2, 1, 0, true});
        v.requiredNumber(x, "x", TRange::closed(-5, 5, "m"), "required");
        v.optionalNumber(heading_deg, "heading_deg", TRange::closed(-180, 180, "deg"),
                         "optional");
        v.numbers(corners, "corners", TRange::closed(-100, 100, "m"), "x1 y1 x2 y2",
                  TCount{0, 1, 4, false});
        v.include(size);
    }
    void onLoaded() override {
        if (name.empty())
            name = section;
    }
};
const char* kShape =
    "[Box]\ncentre = 1 2\noutline = 0 0 1 0 1 1\nx = 3\nwidth = 4\nheight = 2\n";
}  // namespace

// Required points and numbers, point lists, counted and optional lists, a
// name defaulting to the section's, another struct's keys in the same section.
TEST(CDeclaredOptions, PointsRequiredOptionalAndIncludedKeys) {
    mrpt::config::CConfigFileMemory c(kShape);
    TShapeOptions o;
    o.loadFromConfigFile(c, "Box");
    EXPECT_EQ(o.name, "Box");
    EXPECT_DOUBLE_EQ(o.centre.y, 2);
    ASSERT_EQ(o.outline.size(), 3u);
    EXPECT_DOUBLE_EQ(o.outline[2].x, 1);
    EXPECT_DOUBLE_EQ(o.x, 3);
    EXPECT_FALSE(o.heading_deg.has_value());
    EXPECT_DOUBLE_EQ(o.size.width, 4);
    EXPECT_EQ(o.size.section, "Box");
    o.validate();
    // saved and loaded back in memory: the same, the absent optional absent
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "Box");
    EXPECT_EQ(saved.getContent().find("heading_deg"), std::string::npos);
    TShapeOptions p;
    p.loadFromConfigFile(saved, "Box");
    EXPECT_DOUBLE_EQ(p.outline[1].x, 1);
    EXPECT_DOUBLE_EQ(p.size.height, 2);
    // the included struct's rules are checked with the host's
    p.size.height = 5;
    EXPECT_THROW(p.validate(), std::exception);

    auto loadError = [](const std::string& text) {
        mrpt::config::CConfigFileMemory bad(text);
        TShapeOptions q;
        try {
            q.loadFromConfigFile(bad, "Box");
            q.validate();
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_NE(loadError("[Box]\ncentre = 1 2\noutline = 0 0 1 1\n")
                  .find("[Box] x: required key is missing"),
              std::string::npos);
    EXPECT_NE(loadError("[Box]\noutline = 0 0 1 1\nx = 1\n")
                  .find("[Box] centre: required key is missing"),
              std::string::npos);
    EXPECT_NE(loadError("[Box]\ncentre = 1 2\noutline = 0 0 1\nx = 1\n").find("outline"),
              std::string::npos);
    EXPECT_NE(
        loadError("[Box]\ncentre = 1 2\noutline = 0 0 1 1\nx = 1\ncorners = 1 2 3\n")
            .find("needs exactly 4 numbers"),
        std::string::npos);
    EXPECT_NE(loadError("[Box]\ncentre = 1 2\noutline = 0 0 1 1\nx = 1\nheading_deg = "
                        "200\n")
                  .find("[Box] heading_deg"),
              std::string::npos);
    EXPECT_EQ(
        loadError("[Box]\ncentre = 1 2\noutline = 0 0 1 1\nx = 1\nheading_deg = 90\n"),
        "(no error)");
}

namespace {
struct TStartOptions : public CDeclaredOptions {
    TStartOptions() { section = "Start"; }
    mrpt::math::TPose2D start{std::nan(""), std::nan(""), std::nan("")};

  protected:
    void declare(Visitor& v) override {
        v.pose(start, "start", TRange::closed(-1e6, 1e6, "m"),
               TRange::closed(-3600, 3600, "deg"), "x y heading_deg");
    }
};
}  // namespace

// A pose: degrees in the file, radians in MRPT's TPose2D, each part's range.
TEST(CDeclaredOptions, APoseHasItsHeadingInDegrees) {
    mrpt::config::CConfigFileMemory c("[Start]\nstart = 1 2 90\n");
    TStartOptions o;
    o.loadFromConfigFile(c, "Start");
    EXPECT_NEAR(o.start.phi, M_PI / 2, 1e-15);
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "Start");
    EXPECT_NE(saved.getContent().find("start = 1 2 90 //"), std::string::npos)
        << saved.getContent();
    for (const char* bad :
         {"[Start]\nstart = 1 2\n", "[Start]\nstart = 1 2 4000\n", "[Start]\nx = 1\n"}) {
        mrpt::config::CConfigFileMemory b(bad);
        TStartOptions p;
        EXPECT_ANY_THROW(p.loadFromConfigFile(b, "Start")) << bad;
    }
}

namespace {
struct TModel : public CDeclaredOptions {
    TModel() { section = "Model"; }
    double p = 0.6;

  protected:
    void declare(Visitor& v) override {
        v.number(p, "p", TRange::closed(0, 1), "a probability");
    }
};
struct TFilesOptions : public CDeclaredOptions {
    TFilesOptions() { section = "Files"; }
    std::vector<std::string> logs;
    std::string model_name;
    TModel model;

  protected:
    void declare(Visitor& v) override {
        v.paths(logs, "logs", "the logs to read");
        v.text(model_name, "model", false, "section of the model ('' = built-in)");
        v.namedSection(model, model_name, "model");
    }
};
}  // namespace

// Paths: quote-aware, saved back with the quotes; a struct from the section
// another key names, saved there, checked in its own section.
TEST(CDeclaredOptions, PathListsAndNamedSections) {
    mrpt::config::CConfigFileMemory c(
        "[Files]\nlogs = a.rawlog \"/b c/d.rawlog\"\nmodel = Laser\n[Laser]\np = 0.9\n");
    TFilesOptions o;
    o.loadFromConfigFile(c, "Files");
    ASSERT_EQ(o.logs.size(), 2u);
    EXPECT_EQ(o.logs[0], "a.rawlog");
    EXPECT_EQ(o.logs[1], "/b c/d.rawlog");
    EXPECT_DOUBLE_EQ(o.model.p, 0.9);
    EXPECT_EQ(o.model.section, "Laser");
    o.validate();
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "Files");
    TFilesOptions p;
    p.loadFromConfigFile(saved, "Files");
    EXPECT_EQ(p.logs, o.logs);
    EXPECT_DOUBLE_EQ(p.model.p, 0.9);
    const auto keys = o.keys();
    ASSERT_EQ(keys.size(), 2u);  // the model's keys are in its own section
    EXPECT_EQ(keys[0].defaultText, "a.rawlog \"/b c/d.rawlog\"");
    EXPECT_EQ(keys[0].range, "file paths");

    o.model.p = 2;
    try {
        o.validate();
        FAIL() << "p = 2 accepted";
    } catch (const CConfigKeyError& e) {
        EXPECT_EQ(e.section, "Laser");
    }

    TFilesOptions builtIn;
    mrpt::config::CConfigFileMemory none("[Files]\nlogs =\n");
    builtIn.loadFromConfigFile(none, "Files");
    EXPECT_TRUE(builtIn.logs.empty());
    EXPECT_DOUBLE_EQ(builtIn.model.p, 0.6);
    EXPECT_EQ(builtIn.model.section, "Files (built-in model)");
    // an empty value is saved without its comment, which would read as the value
    mrpt::config::CConfigFileMemory emptySaved;
    builtIn.saveToConfigFile(emptySaved, "Files");
    TFilesOptions reread;
    reread.logs = {"x"};
    reread.loadFromConfigFile(mrpt::config::CConfigFileMemory(emptySaved.getContent()),
                              "Files");
    EXPECT_TRUE(reread.logs.empty()) << emptySaved.getContent();
    EXPECT_EQ(reread.model_name, "") << emptySaved.getContent();

    for (const char* bad : {"[Files]\nmodel = Nowhere\n", "[Files]\nlogs = \"a b\n"}) {
        mrpt::config::CConfigFileMemory b(bad);
        TFilesOptions q;
        try {
            q.loadFromConfigFile(b, "Files");
            FAIL() << bad;
        } catch (const CBadInputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("[Files]"), std::string::npos) << what;
        }
    }
}

namespace {
struct TSeedOptions : public CDeclaredOptions {
    TSeedOptions() { section = "Run"; }
    uint64_t seed = 1;

  protected:
    void declare(Visitor& v) override { v.seed(seed, "seed", "the run's seed"); }
};
}  // namespace

// A seed is a whole number: 1.5 is refused, not taken as 1.
TEST(CDeclaredOptions, ASeedIsAWholeNumber) {
    TSeedOptions o;
    mrpt::config::CConfigFileMemory c("[Run]\nseed = 9007199254740992\n");
    o.loadFromConfigFile(c, "Run");
    EXPECT_EQ(o.seed, 9007199254740992ULL);
    for (const char* bad : {"[Run]\nseed = 1.5\n", "[Run]\nseed = -1\n"}) {
        TSeedOptions p;
        EXPECT_THROW(p.loadFromConfigFile(mrpt::config::CConfigFileMemory(bad), "Run"),
                     CBadInputError)
            << bad;
    }
}
