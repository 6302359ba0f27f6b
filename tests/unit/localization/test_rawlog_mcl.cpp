#include <risknav/common/CBadInputError.h>
#include <risknav/localization/CRawlogMcl.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::localization;
using risknav::common::CConfigKeyError;

namespace {
// A 10 x 10 m map at 0.05 m, all free but an occupied 2 x 10 m band at x in
// [8, 10] (default KLD bins: 0.10 m x 10 deg).
mrpt::maps::COccupancyGridMap2D makeMap() {
    mrpt::maps::COccupancyGridMap2D g(0, 10, 0, 10, 0.05);
    g.fill(1.0f);
    for (int x = g.x2idx(8.0); x < int(g.getSizeX()); x++)
        for (unsigned y = 0; y < g.getSizeY(); y++)
            g.setCell(x, int(y), 0.0f);
    return g;
}

CRawlogMcl poseMcl(double x, double y, double halfXY, double halfPhiDeg, int particles) {
    CRawlogMcl m;
    m.options.init = "pose";
    m.options.initPose = {x, y, 0};
    m.options.init_xy = m.options.init_y = halfXY;
    m.options.init_phi_deg = halfPhiDeg;
    m.options.particles = particles;
    return m;
}
}  // namespace

// The initial region in KLD bins: free area / binXY^2 x heading range / binPHI.
TEST(RawlogMclParticles, InitialRegionInKldBins) {
    const auto g = makeMap();
    // A free 2 x 2 m box, any heading: 41 x 41 cells (both ends included,
    // as resetUniformFreeSpace() draws), 420.25 x 36 bins.
    const double box = 41 * 41 * 0.05 * 0.05 / (0.1 * 0.1);
    EXPECT_NEAR(poseMcl(4, 5, 1, 180, 5000).initialBins(g), box * 36, 1e-3);
    // Half the box on the occupied band: 20 x 41 free cells.
    EXPECT_NEAR(poseMcl(8, 5, 1, 180, 5000).initialBins(g), 20 * 41 * 0.25 * 36, 1e-3);
    // +-10 deg: 2 heading bins.
    EXPECT_NEAR(poseMcl(4, 5, 1, 10, 5000).initialBins(g), box * 2, 1e-3);
    // A point and one heading: one bin.
    EXPECT_DOUBLE_EQ(poseMcl(4, 5, 0, 0, 10).initialBins(g), 1.0);
    // Global: every free cell (x < 8 m), any heading.
    auto m = poseMcl(4, 5, 1, 10, 5000);
    m.options.init = "global";
    const double cells = g.x2idx(8.0) * 200.0;
    EXPECT_NEAR(m.initialBins(g), cells * 0.25 * 36, 0.1);
    // Coarser bins, fewer of them.
    m.kldOptions.KLD_binSize_XY = 0.2;
    EXPECT_NEAR(m.initialBins(g), cells / 16 * 36, 0.1);
}

// Too few start particles for the region: refused naming the key and the bound.
TEST(RawlogMclParticles, TooFewForTheInitialRegionAreRefused) {
    const auto g = makeMap();
    auto m = poseMcl(4, 5, 1, 180, 200);
    const int n = m.minParticles(g);
    EXPECT_EQ(n, int(std::ceil(CRawlogMcl::kMinParticlesPerBin * 420.25 * 36)));
    try {
        m.checkParticles(g);
        FAIL() << "200 particles for 14400 bins accepted";
    } catch (const CConfigKeyError& e) {
        EXPECT_EQ(e.section, "Localization");
        EXPECT_EQ(e.key, "particles");
        EXPECT_EQ(e.value, "200");
        EXPECT_NE(e.rule.find("must be in [" + std::to_string(n) + ", 1e+06]"),
                  std::string::npos)
            << e.rule;
    }
    m.options.particles = n;
    EXPECT_NO_THROW(m.checkParticles(g));
    m.options.particles = n - 1;
    EXPECT_THROW(m.checkParticles(g), CConfigKeyError);
    // Global over the whole map needs more.
    m.options.init = "global";
    m.options.particles = n;
    EXPECT_THROW(m.checkParticles(g), CConfigKeyError);
}

// A small box needs few: the documented minimum of 10 holds there.
TEST(RawlogMclParticles, SmallRegionTakesTheDocumentedMinimum) {
    const auto g = makeMap();
    EXPECT_EQ(poseMcl(4, 5, 0, 0, 10).minParticles(g), 10);
    EXPECT_NO_THROW(poseMcl(4, 5, 0.1, 5, 10).checkParticles(g));
}
