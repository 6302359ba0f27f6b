// The nav options declared once (CDeclaredOptions): config/risknav-navigate.ini
// documents every key each declares, with its default.
#include <risknav/common/CBadInputError.h>
#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CAfraidExperiment.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/nav/TNavigateOptions.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

using namespace risknav;

namespace {
const std::string kDoc = "config/risknav-navigate.ini";

/** The "; key = value" lines of a section documented commented out, from
 * "; [section]" to the next line not starting "; ". */
std::map<std::string, std::string> commentedSection(const std::string& section) {
    std::map<std::string, std::string> keys;
    bool in = false;
    for (const auto& line : test::readLines(test::sourcePath(kDoc))) {
        if (line.rfind("; [" + section + "]", 0) == 0)
            in = true;
        else if (in && line.rfind("; ", 0) != 0)
            break;
        else if (in && line.find('=') != std::string::npos) {
            std::istringstream l(line.substr(2));
            std::string key, eq, value;
            l >> key >> eq >> value;
            keys[key] = value;
        }
    }
    return keys;
}
}  // namespace

TEST(CRiskAwareReactiveNavOptions,
     TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    mrpt::config::CConfigFileMemory doc(test::readFile(test::sourcePath(kDoc)));
    const nav::CRiskAwareReactiveNav::TOptions defaults;
    const auto keys = defaults.keys();
    ASSERT_EQ(keys.size(), 12u);
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists("CRiskAwareReactiveNav", k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        if (k.key == "speed_limiters")  // none by default; the file names one
            continue;
        const std::string v = doc.read_string("CRiskAwareReactiveNav", k.key, "");
        EXPECT_EQ(v.substr(0, v.find_first_of(" \t/")), k.defaultText) << k.key;
    }
    // the limiter list is held as its text, and loads back what it saves
    nav::CRiskAwareReactiveNav::TOptions o;
    o.speed_limiters = {"CStoppingDistanceLimiter", "risknav::nav::CAfraidSpeedLimiter"};
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "CRiskAwareReactiveNav");
    // (as text: MRPT keeps a padded name in memory)
    const mrpt::config::CConfigFileMemory text(saved.getContent());
    nav::CRiskAwareReactiveNav::TOptions back;
    back.loadFromConfigFile(text, "CRiskAwareReactiveNav");
    EXPECT_EQ(back.speed_limiters, o.speed_limiters);
    EXPECT_EQ(o.keys()[0].defaultText,
              "CStoppingDistanceLimiter risknav::nav::CAfraidSpeedLimiter");
}

TEST(CAfraidSpeedLimiterOptions, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    // [CAfraidSpeedLimiter] is documented commented out (the run names no
    // such limiter); its kernel keys are TKrrOptions', declared with its own
    auto documented = commentedSection("CAfraidSpeedLimiter");
    const auto keys = nav::CAfraidSpeedLimiter::TOptions().keys();
    ASSERT_EQ(keys.size(), 8u);
    EXPECT_EQ(documented.size(), keys.size());
    for (const auto& k : keys) {
        ASSERT_TRUE(documented.count(k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        if (k.key != "afraid_file") {  // required: no default
            EXPECT_EQ(documented[k.key], k.defaultText) << k.key;
        }
    }
    EXPECT_EQ(keys[0].key, "afraid_file");
    EXPECT_EQ(keys[5].key, "kernel_bandwidth");
}

TEST(CAfraidSpeedLimiterOptions, RangesAndRulesNameTheLimitersSection) {
    nav::CAfraidSpeedLimiter::TOptions o;
    auto expectBad = [&](const std::string& key) {
        try {
            o.validate();
            ADD_FAILURE() << key << " accepted";
        } catch (const common::CConfigKeyError& e) {
            EXPECT_EQ(e.section, "CAfraidSpeedLimiter");
            EXPECT_EQ(e.key, key);
        }
    };
    expectBad("afraid_file");  // required
    o.afraid_file = "learned.afraid";
    EXPECT_NO_THROW(o.validate());
    o.krr.bandwidth = 0;
    expectBad("kernel_bandwidth");
    o.krr.bandwidth = 0.5;
    o.v_safe = 1;
    expectBad("v_safe");  // above v_max
}

namespace {
/** The value as documented: before its "//" comment, trimmed. */
std::string documentedValue(std::string v) {
    v = v.substr(0, v.find("//"));
    v.erase(v.find_last_not_of(" \t") + 1);
    v.erase(0, v.find_first_not_of(" \t") == std::string::npos
                   ? v.size()
                   : v.find_first_not_of(" \t"));
    return v;
}

/** The same numbers ("1600000000" = "1.6e+09"), else the same text. */
bool sameValue(const std::string& a, const std::string& b) {
    std::istringstream ia(a), ib(b);
    std::vector<double> na, nb;
    for (double x; ia >> x;)
        na.push_back(x);
    for (double x; ib >> x;)
        nb.push_back(x);
    if (ia.eof() && ib.eof() && !na.empty())
        return na == nb;
    return a == b;
}

/** Every declared key documented in `documented`, with a doc, and the
 * default's value except for the keys in `example`. */
void expectDocumented(
    const std::vector<common::CDeclaredOptions::TKey>& keys,
    const std::function<std::optional<std::string>(const std::string&)>& documented,
    const std::set<std::string>& example) {
    for (const auto& k : keys) {
        const auto v = documented(k.key);
        ASSERT_TRUE(v.has_value()) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        if (!example.count(k.key)) {
            EXPECT_TRUE(sameValue(documentedValue(*v), k.defaultText))
                << k.key << ": documented '" << *v << "', default '" << k.defaultText
                << "'";
        }
    }
}

/** "; key = value // doc" lines of a commented-out section, whole values. */
std::function<std::optional<std::string>(const std::string&)> commented(
    const std::string& section) {
    std::map<std::string, std::string> keys;
    bool in = false;
    for (const auto& line : test::readLines(test::sourcePath(kDoc))) {
        if (line.rfind("; [" + section + "]", 0) == 0)
            in = true;
        else if (in && line.rfind("; ", 0) != 0)
            break;
        else if (in && line.find('=') != std::string::npos &&
                 line.find('=') < line.find("//")) {
            const auto eq = line.find('=');
            keys[documentedValue(line.substr(2, eq - 2))] = line.substr(eq + 1);
        }
    }
    return [keys](const std::string& k) -> std::optional<std::string> {
        const auto it = keys.find(k);
        return it == keys.end() ? std::nullopt : std::optional<std::string>(it->second);
    };
}
}  // namespace

TEST(TNavigateOptions, TheDocumentedConfigHoldsEveryDeclaredKey) {
    mrpt::config::CConfigFileMemory doc(test::readFile(test::sourcePath(kDoc)));
    const auto keys = nav::TNavigateOptions().keys();
    ASSERT_EQ(keys.size(), 25u);
    expectDocumented(keys,
                     [&](const std::string& k) -> std::optional<std::string> {
                         if (!doc.keyExists("Navigate", k))
                             return std::nullopt;
                         return doc.read_string("Navigate", k, "");
                     },
                     // the example's route, start, run and engine
                     {"start", "goals", "duration_max", "seed", "engine_config"});
    EXPECT_EQ(keys[0].key, "start");
    EXPECT_EQ(keys[10].key, "start_sigma");
}

// start_sigma: degrees in the file, radians held; each part its own range.
TEST(TNavigateOptions, StartSigmaHasItsHeadingInDegreesAndASeedIsWhole) {
    mrpt::config::CConfigFileMemory c(
        "[Navigate]\nstart = 1 2 90\ngoals = 3 4\nlocalization = odometry\n"
        "start_sigma = 0.1 0.2 10\nseed = 7\n");
    nav::TNavigateOptions o;
    o.loadFromConfigFile(c, "Navigate");
    EXPECT_NEAR(o.start.phi, M_PI / 2, 1e-15);
    EXPECT_NEAR(o.start_sigma[2], 10 * M_PI / 180, 1e-15);
    EXPECT_EQ(o.seed, 7u);
    EXPECT_NO_THROW(o.validate());
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "Navigate");
    nav::TNavigateOptions back;
    back.loadFromConfigFile(saved, "Navigate");
    EXPECT_EQ(back.start_sigma, o.start_sigma);  // the same bits
    EXPECT_EQ(back.start, o.start);
    o.start_sigma[2] = 91 * M_PI / 180;
    EXPECT_THROW(o.validate(), common::CConfigKeyError);
    o.start_sigma = {11, 0, 0};
    EXPECT_THROW(o.validate(), common::CConfigKeyError);
    for (const char* bad : {"[Navigate]\ngoals = 3 4\n",  // no start
                            "[Navigate]\nstart = 1 2 90\nseed = 1.5\n",
                            "[Navigate]\nstart = 1 2 90\nstart_sigma = 0 0\n"}) {
        nav::TNavigateOptions p;
        EXPECT_THROW(
            p.loadFromConfigFile(mrpt::config::CConfigFileMemory(bad), "Navigate"),
            common::CBadInputError)
            << bad;
    }
}

TEST(TAfraidExperimentOptions, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    const auto keys = nav::TAfraidExperimentOptions().keys();
    ASSERT_EQ(keys.size(), 7u);
    expectDocumented(keys, commented("AfraidExperiment"), {});
    // whole, distinct seeds
    for (const char* bad :
         {"[AfraidExperiment]\nseeds = 1 2.5\n", "[AfraidExperiment]\nseeds = 1 -2\n"}) {
        nav::TAfraidExperimentOptions p;
        EXPECT_THROW(p.loadFromConfigFile(mrpt::config::CConfigFileMemory(bad),
                                          "AfraidExperiment"),
                     common::CBadInputError)
            << bad;
    }
    nav::TAfraidExperimentOptions o;
    o.seeds = {1, 2, 1};
    EXPECT_THROW(o.validate(), common::CConfigKeyError);
    o.seeds = {3, 1000000};
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "AfraidExperiment");
    nav::TAfraidExperimentOptions back;
    back.loadFromConfigFile(saved, "AfraidExperiment");
    EXPECT_EQ(back.seeds, o.seeds);
}

TEST(CAdaptiveSpeedLimiterOptions,
     TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    const auto keys = nav::CAdaptiveSpeedLimiter::TOptions().keys();
    ASSERT_EQ(keys.size(), 20u);  // [SpeedControl]'s 9 included
    expectDocumented(keys, commented("CAdaptiveSpeedLimiter"), {});
}

// laser_model names another section holding a sensor model: loaded from it,
// saved into it, checked there; a missing one is an error naming the key.
TEST(CAdaptiveSpeedLimiterOptions, TheModelsComeFromTheSectionsTheyName) {
    mrpt::config::CConfigFileMemory c(
        "[L]\nlaser_model = MyLaser\nuse_range2 = false\n"
        "[MyLaser]\np_obs_given_obstacle = 0.8\np_obs_given_free = 0.25\n");
    nav::CAdaptiveSpeedLimiter::TOptions o;
    o.loadFromConfigFile(c, "L");
    EXPECT_EQ(o.laser.section, "MyLaser");
    EXPECT_DOUBLE_EQ(o.laser.p_obs_given_obstacle, 0.8);
    EXPECT_EQ(o.range2.section, "L (built-in range2_model)");
    EXPECT_NO_THROW(o.validate());
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "L");
    nav::CAdaptiveSpeedLimiter::TOptions back;
    back.loadFromConfigFile(saved, "L");
    EXPECT_DOUBLE_EQ(back.laser.p_obs_given_free, 0.25);
    o.laser.p_obs_given_obstacle = 2;
    try {
        o.validate();
        ADD_FAILURE() << "p_obs_given_obstacle = 2 accepted";
    } catch (const common::CConfigKeyError& e) {
        EXPECT_EQ(e.section, "MyLaser");
    }
    try {
        nav::CAdaptiveSpeedLimiter::TOptions p;
        p.loadFromConfigFile(
            mrpt::config::CConfigFileMemory("[L]\nrange2_model = Nope\n"), "L");
        ADD_FAILURE() << "a missing model section accepted";
    } catch (const common::CBadInputError& e) {
        EXPECT_NE(
            std::string(e.what()).find("[L] range2_model = 'Nope': no section [Nope]"),
            std::string::npos)
            << e.what();
    }
}
