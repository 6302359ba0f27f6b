// squaredDistanceTransform() against brute force (every cell to every
// source, and to the ring outside the grid when it counts).
#include <risknav/mapping/distance_transform.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace risknav::mapping;

namespace {
std::vector<int32_t> bruteForce(const std::vector<uint8_t>& src, int w, int h,
                                bool border) {
    std::vector<int32_t> out(src.size(), kNoSource);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            int64_t best = kNoSource;
            for (int sj = -1; sj <= h; sj++)
                for (int si = -1; si <= w; si++) {
                    const bool ring = si < 0 || sj < 0 || si == w || sj == h;
                    if (ring ? !border : !src[size_t(sj) * w + si])
                        continue;
                    best = std::min<int64_t>(
                        best, int64_t(si - i) * (si - i) + int64_t(sj - j) * (sj - j));
                }
            out[size_t(j) * w + i] = int32_t(best);
        }
    return out;
}
}  // namespace

TEST(SquaredDistanceTransform, MatchesBruteForceOnRandomGrids) {
    std::mt19937 rng(7);
    int cases = 0;
    for (const auto& [w, h] :
         {std::pair{1, 1}, {1, 9}, {9, 1}, {17, 23}, {40, 40}, {64, 31}})
        for (const double density : {0.0, 0.002, 0.03, 0.3, 1.0})
            for (const bool border : {false, true}) {
                std::vector<uint8_t> src(size_t(w) * h);
                std::bernoulli_distribution on(density);
                for (auto& s : src)
                    s = on(rng);
                std::vector<int32_t> fast;
                squaredDistanceTransform(src, w, h, border, fast);
                ASSERT_EQ(fast, bruteForce(src, w, h, border))
                    << w << " x " << h << " density " << density << " border " << border;
                cases++;
            }
    EXPECT_EQ(cases, 60);
}

TEST(SquaredDistanceTransform, NoSourceAndOneSource) {
    std::vector<uint8_t> src(5 * 4, 0);
    std::vector<int32_t> d;
    squaredDistanceTransform(src, 5, 4, false, d);
    EXPECT_TRUE(
        std::all_of(d.begin(), d.end(), [](int32_t v) { return v == kNoSource; }));
    src[size_t(2) * 5 + 1] = 1;  // (i, j) = (1, 2)
    squaredDistanceTransform(src, 5, 4, false, d);
    EXPECT_EQ(d[size_t(2) * 5 + 1], 0);
    EXPECT_EQ(d[size_t(0) * 5 + 4], 3 * 3 + 2 * 2);
    EXPECT_EQ(d[size_t(3) * 5 + 0], 1 + 1);
    // the ring: a corner cell is 1 from it
    squaredDistanceTransform(std::vector<uint8_t>(size_t(7) * 7, 0), 7, 7, true, d);
    EXPECT_EQ(d[0], 1);
    EXPECT_EQ(d[size_t(3) * 7 + 3], 16);
    EXPECT_THROW(squaredDistanceTransform(src, 4, 4, false, d), std::invalid_argument);
}

TEST(BoundedSquaredDistanceTransform, IsTheFullTransformWithinReachAndNoneBeyond) {
    std::mt19937 rng(11);
    int cases = 0;
    for (const auto& [w, h] : {std::pair{1, 1}, {1, 9}, {9, 1}, {17, 23}, {40, 40}})
        // dense sources too: a clearance row is mostly non-free cells,
        // whose value the row pass skips (only between the first and last
        // non-source cells of a row is a minimum taken)
        for (const double density : {0.0, 0.002, 0.03, 0.3, 0.7, 0.95, 1.0})
            for (const bool border : {false, true})
                for (const int reach : {0, 1, 3, 9, 50, 127, 128}) {
                    std::vector<uint8_t> src(size_t(w) * h);
                    std::bernoulli_distribution on(density);
                    for (auto& s : src)
                        s = on(rng);
                    auto expected = bruteForce(src, w, h, border);
                    for (auto& v : expected)
                        if (v > reach * reach)
                            v = kNoSource;
                    std::vector<int32_t> bounded;
                    boundedSquaredDistanceTransform(src, w, h, border, reach, bounded);
                    ASSERT_EQ(bounded, expected)
                        << w << " x " << h << " density " << density << " border "
                        << border << " reach " << reach;
                    cases++;
                }
    EXPECT_EQ(cases, 490);
    std::vector<int32_t> d;
    EXPECT_THROW(
        boundedSquaredDistanceTransform(std::vector<uint8_t>(16), 4, 4, false, -1, d),
        std::invalid_argument);
    EXPECT_THROW(
        boundedSquaredDistanceTransform(std::vector<uint8_t>(15), 4, 4, false, 2, d),
        std::invalid_argument);
}

TEST(BoundedDistanceTransform, ReadsEachSquaredDistanceThroughTheTable) {
    // a table that tells the squared distances apart (2 d2 + 0.5) and a
    // value for none no entry has: the emitted floats must be the table's
    // entry for the brute-force squared distance within reach, `none` beyond
    std::mt19937 rng(12);
    int cases = 0;
    for (const auto& [w, h] : {std::pair{1, 1}, {9, 1}, {17, 23}, {40, 40}})
        for (const double density : {0.0, 0.03, 0.3, 0.8})
            for (const bool border : {false, true})
                for (const int reach : {0, 3, 9, 128}) {
                    std::vector<uint8_t> src(size_t(w) * h);
                    std::bernoulli_distribution on(density);
                    for (auto& s : src)
                        s = on(rng);
                    std::vector<float> table(size_t(reach) * reach + 1);
                    for (size_t k = 0; k < table.size(); k++)
                        table[k] = 2.0f * float(k) + 0.5f;
                    const auto brute = bruteForce(src, w, h, border);
                    std::vector<float> out;
                    boundedDistanceTransform(src, w, h, border, reach, table, -1.0f, out);
                    ASSERT_EQ(out.size(), brute.size());
                    for (size_t k = 0; k < out.size(); k++)
                        ASSERT_EQ(out[k], brute[k] <= reach * reach
                                              ? table[size_t(brute[k])]
                                              : -1.0f)
                            << w << " x " << h << " reach " << reach << " cell " << k;
                    cases++;
                }
    EXPECT_EQ(cases, 128);
    std::vector<float> d;
    EXPECT_THROW(boundedDistanceTransform(std::vector<uint8_t>(16), 4, 4, false, 2,
                                          std::vector<float>(4), 0.0f, d),
                 std::invalid_argument);
}
