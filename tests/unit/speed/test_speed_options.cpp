// [SpeedControl]'s declared keys against the documented config.
#include <risknav/common/config_read.h>
#include <risknav/speed/TSpeedControlOptions.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <sstream>

using namespace risknav::speed;

namespace {
// The same numbers (the file may write 0.30 for 0.3), else the same words.
bool sameValue(const std::string& a, const std::string& b) {
    std::istringstream ia(a), ib(b);
    std::string x, y;
    for (;;) {
        const bool hx = bool(ia >> x), hy = bool(ib >> y);
        if (!hx || !hy)
            return hx == hy;
        double dx = 0, dy = 0;
        if (risknav::common::parseNumber(x, dx) && risknav::common::parseNumber(y, dy)
                ? dx != dy
                : x != y)
            return false;
    }
}
}  // namespace

TEST(TSpeedControlOptions, TheDocumentedConfigHoldsEveryDeclaredKeyWithItsDefault) {
    // config/risknav-explore.ini documents [SpeedControl] key by key, with
    // the defaults
    mrpt::config::CConfigFileMemory doc(
        risknav::test::readFile(risknav::test::sourcePath("config/risknav-explore.ini")));
    const TSpeedControlOptions defaults;
    const auto keys = defaults.keys();
    ASSERT_EQ(keys.size(), 9u);
    for (const auto& k : keys) {
        ASSERT_TRUE(doc.keyExists("SpeedControl", k.key)) << k.key;
        EXPECT_FALSE(k.doc.empty()) << k.key;
        const std::string v = doc.read_string("SpeedControl", k.key, "");
        EXPECT_TRUE(sameValue(v.substr(0, v.find("//")), k.defaultText))
            << k.key << ": '" << v << "' vs '" << k.defaultText << "'";
    }
    // the lists are written as they are read, and load back
    mrpt::config::CConfigFileMemory saved;
    defaults.saveToConfigFile(saved, "SpeedControl");
    const mrpt::config::CConfigFileMemory text(saved.getContent());
    TSpeedControlOptions back;
    back.speeds = {1};
    back.margins = {0};
    back.loadFromConfigFile(text, "SpeedControl");
    EXPECT_EQ(back.speeds, defaults.speeds);
    EXPECT_EQ(back.margins, defaults.margins);
    EXPECT_NO_THROW(back.validate());
}
