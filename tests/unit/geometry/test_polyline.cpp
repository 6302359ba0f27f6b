// Polylines of risknav::geometry: length, Douglas-Peucker, segment test.
#include <risknav/geometry/polyline.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

using namespace risknav::geometry;
using mrpt::math::TPoint2D;

namespace {
// Distance from p to the segment a-b.
double segDist(const TPoint2D& p, const TPoint2D& a, const TPoint2D& b) {
    const double vx = b.x - a.x, vy = b.y - a.y, L2 = vx * vx + vy * vy;
    const double t =
        L2 > 0 ? std::clamp(((p.x - a.x) * vx + (p.y - a.y) * vy) / L2, 0.0, 1.0) : 0.0;
    return std::hypot(p.x - (a.x + t * vx), p.y - (a.y + t * vy));
}

// A noisy random walk (x increasing).
std::vector<TPoint2D> noisyWalk(std::mt19937_64& rng, size_t n) {
    std::normal_distribution<double> noise(0, 0.2);
    std::vector<TPoint2D> p;
    double y = 0;
    for (size_t i = 0; i < n; i++) {
        y += noise(rng);
        p.emplace_back(0.1 * double(i), y);
    }
    return p;
}
}  // namespace

TEST(PolylineLength, SumsSegments) {
    EXPECT_EQ(polylineLength({}), 0.0);
    EXPECT_EQ(polylineLength({{1, 2}}), 0.0);
    EXPECT_DOUBLE_EQ(polylineLength({{0, 0}, {3, 4}}), 5.0);
    EXPECT_DOUBLE_EQ(polylineLength({{0, 0}, {3, 4}, {3, 4}, {3, 0}, {0, 0}}), 12.0);
}

TEST(DouglasPeucker, ToleranceRespectedAndEndpointsKept) {
    std::mt19937_64 rng(3);
    for (double tol : {0.0, 0.05, 0.2, 1.0}) {
        for (int trial = 0; trial < 20; trial++) {
            const auto pts = noisyWalk(rng, 5 + size_t(trial) * 7);
            const auto out = simplifyDouglasPeucker(pts, tol);
            ASSERT_GE(out.size(), 2u);
            EXPECT_EQ(out.front(), pts.front());
            EXPECT_EQ(out.back(), pts.back());
            // The output is a subsequence of the input, and every dropped
            // point lies within tol of the segment that replaces it.
            size_t j = 0;
            for (size_t k = 0; k + 1 < out.size(); k++) {
                while (j < pts.size() && !(pts[j] == out[k]))
                    j++;
                ASSERT_LT(j, pts.size()) << "not a subsequence";
                size_t m = j + 1;
                while (m < pts.size() && !(pts[m] == out[k + 1])) {
                    EXPECT_LE(segDist(pts[m], out[k], out[k + 1]), tol + 1e-12)
                        << "tol " << tol << " trial " << trial;
                    m++;
                }
                ASSERT_LT(m, pts.size()) << "not a subsequence";
                j = m;
            }
            if (tol == 0.0) {
                EXPECT_GT(out.size(), pts.size() / 2);  // noise: little to drop
            }
            if (tol == 1.0) {
                EXPECT_LT(out.size(), pts.size());
            }
        }
    }
}

TEST(DouglasPeucker, StraightLineCollapsesShortInputsStay) {
    std::vector<TPoint2D> line;
    for (int i = 0; i <= 10; i++)
        line.emplace_back(i, 2 * i);
    const auto out = simplifyDouglasPeucker(line, 1e-9);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0], line.front());
    EXPECT_EQ(out[1], line.back());
    EXPECT_TRUE(simplifyDouglasPeucker({}, 0.1).empty());
    EXPECT_EQ(simplifyDouglasPeucker({{1, 1}, {5, 5}}, 10).size(), 2u);
    // A closed loop (first == last): distances are taken from the first point.
    const auto loop = simplifyDouglasPeucker({{0, 0}, {1, 0}, {1, 1}, {0, 0}}, 0.8);
    EXPECT_EQ(loop.size(), 3u);
}

TEST(DouglasPeucker, ShortcutTestKeepsCorners) {
    // An L-shaped corridor: the chord from its start to its end is refused
    // (it would cross the wall), so the corner stays even with a huge tolerance.
    const std::vector<TPoint2D> l = {{0, 0}, {0, 1}, {0, 2}, {1, 2}, {2, 2}};
    EXPECT_EQ(simplifyDouglasPeucker(l, 100).size(), 2u);
    const auto noChord = [](const TPoint2D& a, const TPoint2D& b) {
        return a.x == b.x || a.y == b.y;  // axis-parallel shortcuts only
    };
    const auto out = simplifyDouglasPeucker(l, 100, noChord);
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[1], TPoint2D(0, 2));
}

TEST(SegmentFree, SamplesAgainstThePredicate) {
    // A disc obstacle of radius 0.5 at (5, 0).
    const auto disc = [](double x, double y) { return std::hypot(x - 5, y) < 0.5; };
    EXPECT_FALSE(segmentFree(0, 0, 10, 0, 0.1, disc));
    EXPECT_TRUE(segmentFree(0, 1, 10, 1, 0.1, disc));
    EXPECT_TRUE(segmentFree(0, 0, 4, 0, 0.1, disc));
    // A step coarser than the obstacle can miss it (here only the ends 0 and
    // 10 are sampled): the step is the caller's resolution.
    EXPECT_TRUE(segmentFree(0, 0, 10, 0, 10, disc));
    // Both ends are tested.
    EXPECT_FALSE(segmentFree(5, 0, 7, 0, 1, disc));
    EXPECT_FALSE(segmentFree(7, 0, 5, 0, 1, disc));
    // n + 1 samples, n = ceil(length / step); a point is tested (twice).
    int calls = 0;
    const auto count = [&](double, double) {
        calls++;
        return false;
    };
    EXPECT_TRUE(segmentFree(0, 0, 1, 0, 0.25, count));
    EXPECT_EQ(calls, 5);
    calls = 0;
    EXPECT_TRUE(segmentFree(2, 2, 2, 2, 0.25, count));
    EXPECT_EQ(calls, 2);
    EXPECT_THROW(segmentFree(0, 0, 1, 0, 0.0, count), std::invalid_argument);
    EXPECT_THROW(segmentFree(0, 0, 1, 0, std::nan(""), count), std::invalid_argument);
}
