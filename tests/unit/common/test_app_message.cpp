// The one-line error of every app: quoted paths and names are clipped as
// config values are.
#include <risknav/common/CAppRunner.h>

#include <gtest/gtest.h>
#include <opencv2/core/utils/logger.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "test_support.h"

using namespace risknav::common;

TEST(AppMessage, LongPathIsClipped) {
    const std::string path = "/data/" + std::string(1 << 20, 'a') + ".rawlog";
    const std::string line = firstLine(path + ": rawlog does not exist");
    EXPECT_LT(line.size(), 400u);
    EXPECT_EQ(line.rfind("/data/aaa", 0), 0u);  // its head stays
    EXPECT_NE(line.find("... (" + std::to_string(path.size()) + " bytes)"),
              std::string::npos);
    EXPECT_NE(line.find(": rawlog does not exist"), std::string::npos);
}

TEST(AppMessage, LongNameWithSpacesKeepsHeadAndTail) {
    std::string name;
    for (int i = 0; i < 2'000'000; i++)
        name += "ab ";
    const std::string line = firstLine("x.rawlog: scan '" + name + "' has maxRange -1");
    EXPECT_LT(line.size(), 1400u);
    EXPECT_EQ(line.rfind("x.rawlog: scan 'ab ab", 0), 0u);
    EXPECT_NE(line.find("' has maxRange -1"), std::string::npos);
    EXPECT_EQ(line.find('\n'), std::string::npos);
}

TEST(AppMessage, ShortMessageUnchanged) {
    const std::string m =
        "corridor.ini: [Localization] particles = '5': out of range [10, 1e+06]";
    EXPECT_EQ(firstLine(m), m);
    // a run of 256 bytes is not clipped, nor a value clipped already
    const std::string run(256, 'b');
    EXPECT_EQ(firstLine(run + ": x"), run + ": x");
    const std::string clipped = "a.ini: [S] k = '" + std::string(200, 'c') +
                                "... (1048576 bytes)': file not found";
    EXPECT_EQ(firstLine(clipped), clipped);
}

// A failure inside the app is its one line: OpenCV's own log lines (such as
// its warning when it cannot write an image) stay off stderr.
TEST(AppMessage, OpenCvLinesStayOffStderr) {
    const std::string dir = risknav::test::freshDir("cvlog");
    risknav::test::writeFile(dir + "/a.ini", "[A]\n");
    std::vector<std::string> args = {"risknav-demo", "-q", "-o", dir + "/out",
                                     dir + "/a.ini"};
    std::vector<char*> argv;
    for (auto& a : args)
        argv.push_back(a.data());
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_INFO);
    ::testing::internal::CaptureStderr();
    const int rc = runApp(int(argv.size()), argv.data(), {"risknav-demo", "", ""},
                          [](const TAppContext&) {
                              CV_LOG_WARNING(NULL, "imwrite_('x.png'): can't write data");
                              throw std::runtime_error("cannot write x.png: disk full");
                          });
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(rc, 1);
    EXPECT_EQ(err, "risknav-demo: runtime error: cannot write x.png: disk full\n");
}
