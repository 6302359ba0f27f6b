#include <risknav/common/stopping.h>

#include <gtest/gtest.h>

using risknav::common::stoppingDistance;

// Choi et al. (002) Table 1: measured stopping distances with t_delay = 0.9 s
// and a = 1.0 m/s^2 (PAPER_NOTES M3 erratum: d_brake = v^2 / (2 a)).
TEST(StoppingDistance, ReproducesTable1Within5cm) {
    EXPECT_NEAR(stoppingDistance(0.8, 0.9, 1.0), 1.01, 0.05);
    EXPECT_NEAR(stoppingDistance(0.5, 0.9, 1.0), 0.58, 0.05);
    EXPECT_NEAR(stoppingDistance(0.2, 0.9, 1.0), 0.20, 0.05);
    // and the exact model values of PAPER_NOTES
    EXPECT_NEAR(stoppingDistance(0.8, 0.9, 1.0), 1.04, 1e-12);
    EXPECT_NEAR(stoppingDistance(0.5, 0.9, 1.0), 0.575, 1e-12);
    EXPECT_DOUBLE_EQ(stoppingDistance(0.0, 0.9, 1.0), 0.0);
    EXPECT_DOUBLE_EQ(stoppingDistance(-1.0, 0.9, 1.0), 0.0);
}
