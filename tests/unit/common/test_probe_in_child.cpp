#include <risknav/common/probe_in_child.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

using namespace risknav::common;

TEST(probeInChild, ReportsWhereTheChildDiedAndNothingWhenItFinished) {
    // dies at unit 3 (a real segfault), finishes, throws: only the first counts
    const auto died = probeInChild([](const TProbeProgress& progress) {
        for (std::uint64_t i = 0; i < 3; i++)
            progress(i + 1);
        volatile int* p = nullptr;
        *p = 1;
    });
    ASSERT_TRUE(died);
    EXPECT_EQ(*died, 3u);
    EXPECT_FALSE(probeInChild([](const TProbeProgress& progress) { progress(7); }));
    EXPECT_FALSE(
        probeInChild([](const TProbeProgress&) { throw std::runtime_error("x"); }));
    const auto aborted = probeInChild([](const TProbeProgress&) { std::abort(); });
    ASSERT_TRUE(aborted);
    EXPECT_EQ(*aborted, 0u);
}
