// The nav options declared once (CDeclaredOptions): config/risknav-navigate.ini
// documents every key each declares, with its default.
#include <risknav/common/CBadInputError.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>
#include <string>

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
