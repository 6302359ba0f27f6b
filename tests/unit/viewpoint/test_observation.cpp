// The observation strategies of Yamashita et al. (003 sections 3.1-3.3, 004
// section III): exact pose recovery, the worst-case bound against Monte Carlo
// of the image errors, degenerate geometry, landmark visibility.
#include <risknav/viewpoint/observation_model.h>

#include <mrpt/math/wrap2pi.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace risknav::viewpoint;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
namespace geometry = risknav::geometry;

namespace {
// A 10 x 10 m room with landmarks on all four walls, facing inwards.
std::vector<TLandmark> roomLandmarks() {
    std::vector<TLandmark> l;
    int id = 0;
    for (double t : {2.0, 2.3, 4.5, 5.0, 7.0, 7.25}) {
        l.push_back({"S" + std::to_string(id++), t, 0.0, M_PI / 2, 0.05});
        l.push_back({"N" + std::to_string(id++), t, 10.0, -M_PI / 2, 0.05});
        l.push_back({"W" + std::to_string(id++), 0.0, t, 0.0, 0.05});
        l.push_back({"E" + std::to_string(id++), 10.0, t, M_PI, 0.05});
    }
    return l;
}

geometry::CSegmentIndex roomWalls() {
    using risknav::geometry::TSegment;
    return risknav::geometry::CSegmentIndex(
        {TSegment{{0, 0}, {10, 0}}, TSegment{{10, 0}, {10, 10}},
         TSegment{{10, 10}, {0, 10}}, TSegment{{0, 10}, {0, 0}}},
        1.0);
}

double posErr(const TPose2D& a, const TPose2D& b) {
    return std::hypot(a.x - b.x, a.y - b.y);
}
double angErr(const TPose2D& a, const TPose2D& b) {
    return std::abs(mrpt::math::wrapToPi(a.phi - b.phi));
}

struct TCase {
    TPose2D pose;
    std::vector<TObservation> obs;
};

// Random poses in the room with every observation they allow.
std::vector<TCase> randomCases(const std::vector<TLandmark>& lms, const TCameraRig& rig,
                               int n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> xy(2.5, 7.5), ang(-M_PI, M_PI);
    const auto walls = roomWalls();
    std::vector<TCase> out;
    for (int i = 0; i < n; i++) {
        TCase c;
        c.pose = {xy(rng), xy(rng), ang(rng)};
        c.obs = enumerateObservations(c.pose, lms, landmarkViews(c.pose, lms, rig, walls),
                                      rig);
        out.push_back(c);
    }
    return out;
}
}  // namespace

TEST(Observation, ParallelStereoIsTheGeneralTriangulationAtPanZero) {
    // 003 eqs. (1), (3) against the exact rays of both cameras at pan 0.
    const double b = 0.2, f = 3000;
    for (const TPoint2D q :
         {TPoint2D{2.0, 0.3}, TPoint2D{1.2, -0.4}, TPoint2D{3.5, 0.0}}) {
        // Robot at the origin facing +x; left camera at +y.
        const auto [uL, tL] = project({0, b / 2}, 0, q, f);
        const auto [uR, tR] = project({0, -b / 2}, 0, q, f);
        const auto ts = parallelStereo(uL, uR, b, f);
        ASSERT_TRUE(ts);
        EXPECT_NEAR(ts->first, q.x, 1e-9);    // depth t
        EXPECT_NEAR(ts->second, -q.y, 1e-9);  // lateral s, to the right
    }
    EXPECT_FALSE(parallelStereo(10, 10, b, f));  // zero disparity: at infinity
}

TEST(Observation, EveryStrategyRecoversTheTruePoseFromExactMeasurements) {
    const auto lms = roomLandmarks();
    const TCameraRig rig;
    int seen[3] = {0, 0, 0}, degenerate = 0, all = 0;
    for (const auto& c : randomCases(lms, rig, 60, 11))
        for (const auto& o : c.obs) {
            all++;
            if (!worstCaseError(o, c.pose, lms, rig, {1, 1, 1}).ok) {
                degenerate++;  // near-singular geometry, reported as such
                continue;
            }
            const TMeasurement z = predictMeasurement(o, c.pose, lms, rig);
            // The dead-reckoning prior, off by 3 cm and 1 degree, only picks
            // one of several solutions (two circle intersections for B).
            const TPose2D prior{c.pose.x + 0.02, c.pose.y - 0.02, c.pose.phi + 0.017};
            const auto p = solvePose(o, z, lms, rig, prior);
            ASSERT_TRUE(p) << char(o.strategy);
            EXPECT_LT(posErr(*p, c.pose), 1e-6) << char(o.strategy);
            EXPECT_LT(angErr(*p, c.pose), 1e-6) << char(o.strategy);
            seen[size_t(o.strategy) - size_t('A')]++;
        }
    EXPECT_GT(seen[0], 20);
    EXPECT_GT(seen[1], 100);
    EXPECT_GT(seen[2], 20);
    EXPECT_LT(degenerate, all / 20);
}

TEST(Observation, WorstCaseBoundContainsRandomImageErrors) {
    // Monte Carlo: errors drawn uniformly within +-du, +-dr give pose errors
    // within the bound of the sign combinations (up to the solvers'
    // nonlinearity over a few pixels: 0.1 %).
    const auto lms = roomLandmarks();
    const TCameraRig rig;
    const TImageErrors e{2, 2, 2};
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> uni(-1, 1);
    size_t checked = 0, nearBound = 0;
    for (const auto& c : randomCases(lms, rig, 25, 3))
        for (const auto& o : c.obs) {
            const TWorstCase w = worstCaseError(o, c.pose, lms, rig, e);
            if (!w.ok)
                continue;
            EXPECT_GT(w.ePos, 0);
            const TMeasurement z0 = predictMeasurement(o, c.pose, lms, rig);
            const auto dz = measurementErrors(o, e);
            double maxPos = 0;
            for (int d = 0; d < 40; d++) {
                TMeasurement z = z0;
                for (size_t k = 0; k < z.size(); k++)
                    z[k] += dz[k] * uni(rng);
                const auto p = solvePose(o, z, lms, rig, c.pose);
                ASSERT_TRUE(p);
                EXPECT_LE(posErr(*p, c.pose), w.ePos * 1.001 + 1e-12) << char(o.strategy);
                EXPECT_LE(angErr(*p, c.pose), w.dPhi * 1.001 + 1e-12) << char(o.strategy);
                maxPos = std::max(maxPos, posErr(*p, c.pose));
                checked++;
            }
            // The bound is tight, not just large: random draws come near it.
            if (maxPos > 0.5 * w.ePos)
                nearBound++;
        }
    EXPECT_GT(checked, 5000u);
    EXPECT_GT(nearBound, checked / 40 / 2);
}

TEST(Observation, ErrorsGrowWithTheImageErrors) {
    // The bound scales linearly with du = dv = dr while the errors are small
    // (a key equation replaced by a constant would not), and keeps growing for
    // larger ones (stereo's heading from the landmark's two ends, 10 cm
    // apart, saturates: not linear there).
    const auto lms = roomLandmarks();
    const TCameraRig rig;
    size_t n = 0;
    for (const auto& c : randomCases(lms, rig, 10, 8))
        for (const auto& o : c.obs) {
            const TWorstCase a = worstCaseError(o, c.pose, lms, rig, {0.01, 0.01, 0.01});
            const TWorstCase b = worstCaseError(o, c.pose, lms, rig, {0.03, 0.03, 0.03});
            const TWorstCase w1 = worstCaseError(o, c.pose, lms, rig, {1, 1, 1});
            const TWorstCase w3 = worstCaseError(o, c.pose, lms, rig, {3, 3, 3});
            if (!a.ok || !b.ok || !w1.ok || !w3.ok)
                continue;
            EXPECT_GE(w3.ePos, w1.ePos) << char(o.strategy);
            EXPECT_GT(w1.ePos, b.ePos) << char(o.strategy);
            // Linear where the geometry is well conditioned (a hundredth of a
            // pixel moves the pose by less than a millimetre); near-tangent
            // two-landmark rays and near-circle three-landmark geometry are
            // not, by nature.
            if (a.ePos > 1e-3)
                continue;
            EXPECT_NEAR(b.ePos / a.ePos, 3.0, 0.05) << char(o.strategy);
            EXPECT_NEAR(b.dPhi / a.dPhi, 3.0, 0.05) << char(o.strategy);
            n++;
        }
    EXPECT_GT(n, 50u);
}

TEST(Observation, ThreeLandmarksWellSpreadBeatTwoAndStereo) {
    // 003 Table 1, position III: where three landmarks are seen well spread
    // (a pair filling one camera's image, the third square to the side), the
    // three-landmark observation has the smallest error.
    const std::vector<TLandmark> lms{{"1", 2.0, 0.16, M_PI, 0.05},
                                     {"2", 2.0, -0.16, M_PI, 0.05},
                                     {"3", 0.3, 2.0, -M_PI / 2, 0.05}};
    const TCameraRig rig;
    const TPose2D pose{0, 0, 0};
    const geometry::CSegmentIndex none;
    const auto obs =
        enumerateObservations(pose, lms, landmarkViews(pose, lms, rig, none), rig);
    double best[3] = {1e9, 1e9, 1e9};
    for (const auto& o : obs) {
        const auto w = worstCaseError(o, pose, lms, rig, {1, 1, 1});
        if (!w.ok)
            continue;
        auto& b = best[size_t(o.strategy) - size_t('A')];
        b = std::min(b, totalError(w, 0.5));
    }
    ASSERT_LT(best[2], 1e9) << "no three-landmark observation";
    EXPECT_LT(best[2], best[1]);
    EXPECT_LT(best[2], best[0]);
}

TEST(Observation, RobotOnTheCircleOfThreeLandmarksIsDegenerateNotNaN) {
    // Resection is singular when the robot lies on the circle through the
    // three landmarks, and when robot and landmarks lie on one line (the
    // circle's limit). Cameras at the centre (b_r = 0) make both exact.
    TCameraRig rig;
    rig.b_r = 0;
    auto threeLandmark = [](double pan0, double pan1) {
        TObservation o;
        o.strategy = TStrategy::ThreeLandmark;
        o.lm = {{0, 1, 2}};
        o.side = +1;
        o.pan = {{pan0, pan1}};
        return o;
    };
    const TPose2D pose{0, 0, 0};
    // Circle of radius 2 around (0, 2) through the robot at the origin.
    auto on = [](double a) { return TPoint2D{2 * std::cos(a), 2 + 2 * std::sin(a)}; };
    const TPoint2D a = on(-0.3), b = on(-0.2), c = on(M_PI + 0.4);
    std::vector<TLandmark> lms;
    for (const auto& p : {a, b, c})
        lms.push_back({"x", p.x, p.y, std::atan2(-p.y, -p.x), 0.05});
    const double pan0 = (std::atan2(a.y, a.x) + std::atan2(b.y, b.x)) / 2;
    const TWorstCase w = worstCaseError(threeLandmark(pan0, std::atan2(c.y, c.x)), pose,
                                        lms, rig, {1, 1, 1});
    EXPECT_FALSE(w.ok);
    EXPECT_TRUE(std::isfinite(w.ePos) && std::isfinite(w.dPhi));

    // Collinear: the pair ahead on the x axis, the third behind on it.
    const std::vector<TLandmark> line{
        {"p", 2, 0, M_PI, 0.05}, {"q", 3, 0, M_PI, 0.05}, {"r", -2, 0, 0, 0.05}};
    const TWorstCase wl =
        worstCaseError(threeLandmark(0, M_PI), pose, line, rig, {1, 1, 1});
    EXPECT_FALSE(wl.ok);
    EXPECT_TRUE(std::isfinite(wl.ePos) && std::isfinite(wl.dPhi));

    // Moved off the circle, the same landmarks are fine.
    const TPose2D off{0.0, 0.8, 0};
    TObservation o =
        threeLandmark((std::atan2(a.y - 0.8, a.x) + std::atan2(b.y - 0.8, b.x)) / 2,
                      std::atan2(c.y - 0.8, c.x));
    EXPECT_TRUE(worstCaseError(o, off, lms, rig, {1, 1, 1}).ok);
}

TEST(Observation, VisibilityRangeBackSideOcclusionAndFit) {
    TCameraRig rig;
    rig.maxRange = 3;
    const std::vector<TLandmark> lms{
        {"front", 2.0, 0.0, M_PI, 0.05},       // facing the robot
        {"back", 2.0, 1.0, 0.0, 0.05},         // facing away
        {"far", 4.0, -1.0, M_PI, 0.05},        // beyond 3 m
        {"hidden", 2.0, -1.0, M_PI, 0.05},     // behind a wall segment
        {"near", 0.4, 0.3, -M_PI / 2, 0.05}};  // too near to fit the image
    using risknav::geometry::TSegment;
    const geometry::CSegmentIndex walls({TSegment{{1.0, -1.5}, {1.0, -0.2}}}, 0.5);
    const auto v = landmarkViews({0, 0, 0}, lms, rig, walls);
    EXPECT_TRUE(v[0].visible[0] && v[0].visible[1]);
    EXPECT_FALSE(v[1].visible[0] || v[1].visible[1]);
    EXPECT_FALSE(v[2].visible[0] || v[2].visible[1]);
    EXPECT_FALSE(v[3].visible[0] || v[3].visible[1]);
    EXPECT_FALSE(v[4].visible[0] || v[4].visible[1]);
    // Without the wall the hidden one is seen.
    const auto v2 = landmarkViews({0, 0, 0}, lms, rig, geometry::CSegmentIndex());
    EXPECT_TRUE(v2[3].visible[0] && v2[3].visible[1]);
    // Pan limit: a landmark behind the robot needs |pan| ~ 180 degrees.
    rig.panLimit = M_PI / 2;
    const auto v3 = landmarkViews({0, 0, M_PI}, lms, rig, geometry::CSegmentIndex());
    EXPECT_FALSE(v3[0].visible[0] || v3[0].visible[1]);
}
