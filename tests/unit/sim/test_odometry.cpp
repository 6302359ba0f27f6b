#include <risknav/sim/COdometrySim.h>
#include <risknav/sim/odometry_model.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace risknav::sim;

TEST(OdometryModel, WheelsAndTwistAreInverse) {
    const TWheelGeometry g{0.06, 0.065, 0.4};
    double uL, uR, v, w;
    wheelsFromTwist(g, 0.7, -0.3, uL, uR);
    twistFromWheels(g, uL, uR, v, w);
    EXPECT_NEAR(v, 0.7, 1e-12);
    EXPECT_NEAR(w, -0.3, 1e-12);
}

TEST(OdometryModel, ArcIntegrationClosesACircle) {
    mrpt::math::TPose2D p(1, 2, 0.3);
    const int n = 7;  // exact arcs: any step count closes the circle
    for (int i = 0; i < n; i++)
        p = integrateTwist(p, 0.5, 0.25, 2 * M_PI / 0.25 / n);
    EXPECT_NEAR(p.x, 1, 1e-9);
    EXPECT_NEAR(p.y, 2, 1e-9);
    EXPECT_NEAR(p.phi, 0.3, 1e-9);
    const auto q = integrateTwist({0, 0, M_PI / 2}, 2.0, 0.0, 0.5);
    EXPECT_NEAR(q.x, 0, 1e-12);
    EXPECT_NEAR(q.y, 1.0, 1e-12);
}

namespace {
struct TDrift {
    double meanX = 0, meanY = 0, stdX = 0, stdY = 0;
};

// Drives 5 m straight at 0.5 m/s (dt = 0.05 s, 200 steps) with `runs` robots
// whose odometry errors come from the given model; statistics of the final
// odometric position (the truth ends at (5, 0)).
TDrift monteCarlo(const std::string& model, double sigmaR, int runs) {
    std::vector<double> xs, ys;
    for (int r = 0; r < runs; r++) {
        COdometrySim o;
        o.options.error_model = model;
        o.options.sigma_wheel_radius_l = o.options.sigma_wheel_radius_r = sigmaR;
        o.options.sigma_tread = 0.001;
        o.reset({0, 0, 0}, 1000 + r);
        for (int k = 0; k < 200; k++)
            o.step(0.5, 0.0, 0.05);
        xs.push_back(o.pose().x);
        ys.push_back(o.pose().y);
    }
    TDrift d;
    for (int i = 0; i < runs; i++) {
        d.meanX += xs[i] / runs;
        d.meanY += ys[i] / runs;
    }
    for (int i = 0; i < runs; i++) {
        d.stdX += std::pow(xs[i] - d.meanX, 2) / (runs - 1);
        d.stdY += std::pow(ys[i] - d.meanY, 2) / (runs - 1);
    }
    d.stdX = std::sqrt(d.stdX);
    d.stdY = std::sqrt(d.stdY);
    return d;
}
constexpr double R = 0.063, T = 0.399, L = 5.0, v = 0.5, dt = 0.05;
}  // namespace

// Systematic radius errors e_l, e_r ~ N(0, s^2), constant over the run. To first
// order the odometric heading grows as theta(s) = s (e_l - e_r) / (R T), so the
// lateral error is y(L) = L^2 (e_l - e_r) / (2 R T) and the along-track error is
// x(L) - L = -L (e_l + e_r) / (2 R): std(y) = L^2 sqrt(2) s / (2 R T),
// std(x) = L sqrt(2) s / (2 R). The tread error does not act on a straight line.
TEST(OdometryDrift, SystematicModelMatchesItsPrediction) {
    const double s = 1e-4;
    const TDrift d = monteCarlo("systematic", s, 2000);
    const double stdY = L * L * std::sqrt(2.0) * s / (2 * R * T);
    const double stdX = L * std::sqrt(2.0) * s / (2 * R);
    EXPECT_NEAR(d.stdY / stdY, 1.0, 0.10) << d.stdY << " vs " << stdY;
    EXPECT_NEAR(d.stdX / stdX, 1.0, 0.10) << d.stdX << " vs " << stdX;
    EXPECT_NEAR(d.meanY, 0.0, 4 * stdY / std::sqrt(2000.0));
    // Second order: the heading error shortens the along-track distance,
    // E[x] = L - int_0^L E[theta(s)^2] / 2 ds = L - L^3 k^2 / 6, k^2 = 2 s^2 / (R T)^2.
    const double meanX = L - std::pow(L, 3) * (2 * s * s / std::pow(R * T, 2)) / 6;
    EXPECT_NEAR(d.meanX, meanX, 4 * stdX / std::sqrt(2000.0));
}

// Per-step errors (the assumption of Irie et al. eq. 15): each step k adds an
// independent heading increment d_k with var = 2 s^2 (v dt / (R T))^2; step j
// moves along theta_{j-1} + d_j / 2, so y = v dt sum_i d_i (n - i + 1/2) and
// var(y) = (v dt)^2 var(d) sum_{i=1..n} (n - i + 1/2)^2.
TEST(OdometryDrift, PerStepModelMatchesItsPrediction) {
    const double s = 1e-3;
    const TDrift d = monteCarlo("per_step", s, 2000);
    const int n = 200;
    double sum = 0;
    for (int i = 1; i <= n; i++)
        sum += std::pow(n - i + 0.5, 2);
    const double varD = 2 * s * s * std::pow(v * dt / (R * T), 2);
    const double stdY = std::sqrt(std::pow(v * dt, 2) * varD * sum);
    EXPECT_NEAR(d.stdY / stdY, 1.0, 0.10) << d.stdY << " vs " << stdY;
    // The same sigma drifts far less per step than as a constant bias.
    EXPECT_LT(d.stdY, monteCarlo("systematic", s, 300).stdY / 5);
}

TEST(OdometryDrift, NoneIsExact) {
    const TDrift d = monteCarlo("none", 1e-3, 5);
    EXPECT_NEAR(d.meanX, 5.0, 1e-9);
    EXPECT_NEAR(d.stdY, 0.0, 1e-12);
}

TEST(OdometryDrift, SameSeedSameDrift) {
    COdometrySim a, b;
    a.reset({0, 0, 0}, 5);
    b.reset({0, 0, 0}, 5);
    for (int k = 0; k < 50; k++) {
        a.step(0.3, 0.1, 0.05);
        b.step(0.3, 0.1, 0.05);
    }
    EXPECT_EQ(a.pose().x, b.pose().x);
    EXPECT_EQ(a.pose().phi, b.pose().phi);
}
