// engine_config_check: MRPT's own reactive-engine INI, checked before and
// after MRPT loads it, on in-memory configs (the run's keys over MRPT's
// shipped file, as risknav-navigate layers them). The messages are those
// tests/e2e/test_navigate.cpp expects of the app.
#include <risknav/common/CBadInputError.h>
#include <risknav/nav/CLayeredConfig.h>
#include <risknav/nav/CNullRobot.h>
#include <risknav/nav/engine_config_check.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/nav/reactive/CReactiveNavigationSystem.h>
#include <mrpt/system/filesystem.h>

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <string>

using namespace risknav;

namespace {
// MRPT's shipped reactive2d_config.ini: a config MRPT's engine runs with.
const mrpt::config::CConfigFileMemory& mrptEngineFile() {
    static const mrpt::config::CConfigFileMemory file([] {
        std::ifstream f(mrpt::system::find_mrpt_shared_dir() +
                        "config_files/navigation-ptgs/reactive2d_config.ini");
        std::stringstream ss;
        ss << f.rdbuf();
        return ss.str();
    }());
    return file;
}

// The message of the CBadInputError `f` throws ("" when it throws none).
std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const common::CBadInputError& e) {
        return e.what();
    }
    return "";
}

// `keys` over MRPT's file, loaded into MRPT's engine as loadConfigFile()
// does: the text checked first, then the types and values MRPT holds.
std::string loadMessage(const std::string& keys) {
    const mrpt::config::CConfigFileMemory top(keys);
    const nav::CLayeredConfig layered(top, mrptEngineFile());
    nav::CNullRobot robot;
    mrpt::nav::CReactiveNavigationSystem engine(robot, false, false);
    engine.setMinLoggingLevel(mrpt::system::LVL_ERROR);
    return messageOf([&] {
        nav::checkEngineText(layered);
        engine.loadConfigFile(layered);
        nav::checkEngineTypes(layered, engine);
        nav::checkEngineValues(layered, engine);
        nav::checkEngineBuildTime(layered, engine, 0.35, "");
    });
}
}  // namespace

TEST(EngineConfigCheck, MrptsOwnFilePasses) {
    EXPECT_EQ(loadMessage(""), "");
    ASSERT_TRUE(mrptEngineFile().keyExists("CReactiveNavigationSystem", "PTG_COUNT"));
}

TEST(EngineConfigCheck, AFormulaThatDoesNotCompileNamesItsKey) {
    const std::string m = loadMessage(
        "[CMultiObjMotionOpt_Scalarization]\n"
        "scalar_score_formula = colision_free_distance\n");
    EXPECT_EQ(m,
              "[CMultiObjMotionOpt_Scalarization] scalar_score_formula = "
              "'colision_free_distance': does not compile in MRPT's expression parser: "
              "ERR201 - Undefined symbol: 'colision_free_distance'");
    // evaluated for every candidate motion of every cycle: no loops
    EXPECT_NE(loadMessage("[CMultiObjectiveMotionOptimizerBase]\n"
                          "movement_assert1 = for (var i := 0; i < 9; i += 1) {}\n")
                  .find("movement_assert1 = 'for (var i := 0; i < 9; i += 1) {}': no "
                        "loops"),
              std::string::npos);
}

TEST(EngineConfigCheck, AClassMrptCannotMakeIsRefusedBeforeMrptLoadsIt) {
    EXPECT_EQ(loadMessage("[CReactiveNavigationSystem]\n"
                          "PTG0_Type = CParameterizedTrajectoryGenerator\n"),
              "[CReactiveNavigationSystem] PTG0_Type = "
              "'CParameterizedTrajectoryGenerator': not one of MRPT's PTG classes "
              "(CPTG_DiffDrive_C, CPTG_DiffDrive_CC, CPTG_DiffDrive_CCS, "
              "CPTG_DiffDrive_CS, CPTG_DiffDrive_alpha, CPTG_Holo_Blend)");
    EXPECT_EQ(loadMessage("[CReactiveNavigationSystem]\nPTG_COUNT = 2.7\n"),
              "[CReactiveNavigationSystem] PTG_COUNT = '2.7': not an integer");
}

TEST(EngineConfigCheck, AWordForANumberIsCaughtAfterMrptReadItAsZero) {
    EXPECT_EQ(loadMessage("[CHolonomicFullEval]\nTOO_CLOSE_OBSTACLE = abc\n"),
              "[CHolonomicFullEval] TOO_CLOSE_OBSTACLE = 'abc': not a number");
    EXPECT_EQ(loadMessage("[CAbstractPTGBasedReactive]\nuse_delays_model = abc\n"),
              "[CAbstractPTGBasedReactive] use_delays_model = 'abc': must be true or "
              "false");
}

TEST(EngineConfigCheck, ValuesMrptHoldsAreInRange) {
    EXPECT_EQ(loadMessage("[CAbstractPTGBasedReactive]\nsecure_distance_end = 0\n"),
              "[CAbstractPTGBasedReactive] secure_distance_end = '0': must be more "
              "than secure_distance_start = 0.05");
    EXPECT_EQ(loadMessage("[CHolonomicFullEval]\nTOO_CLOSE_OBSTACLE = 1.5\n"),
              "[CHolonomicFullEval] TOO_CLOSE_OBSTACLE = '1.5': must be in [0, 1] "
              "(normalized distance)");
}
