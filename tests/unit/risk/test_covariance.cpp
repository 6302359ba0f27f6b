#include <risknav/risk/CPosePropagator.h>
#include <risknav/risk/odometry_covariance.h>
#include <risknav/risk/path_risk.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace risknav::risk;
using mrpt::math::TPoint2D;

TEST(OdometryCovariance, JacobiansMatchFiniteDifferences) {
    TOdometryModel m;
    const double uL = 3.1, uR = 5.2, h = 1e-7;
    const auto l = jacobianWheelParams(m, uL, uR);
    double v0, w0, v1, w1;
    twistFromWheels(m, uL, uR, v0, w0);
    for (int j = 0; j < 3; j++) {
        TOdometryModel p = m;
        (j == 0 ? p.radiusL : j == 1 ? p.radiusR : p.tread) += h;
        twistFromWheels(p, uL, uR, v1, w1);
        EXPECT_NEAR(l(0, j), (v1 - v0) / h, 1e-5) << j;
        EXPECT_NEAR(l(1, j), (w1 - w0) / h, 1e-5)
            << j;  // erratum: the paper's (27) fails here for j = 2
    }
    const auto jp = jacobianPose(0.7, 0.4, 0.1);
    EXPECT_NEAR(jp(0, 2), -0.1 * 0.4 * std::sin(0.7), 1e-15);
    EXPECT_NEAR(jp(1, 2), 0.1 * 0.4 * std::cos(0.7), 1e-15);
    const auto jv = jacobianVelocity(0.7, 0.1);
    EXPECT_NEAR(jv(0, 0), 0.1 * std::cos(0.7), 1e-15);
    EXPECT_NEAR(jv(2, 1), 0.1, 1e-15);
}

namespace {
// Monte Carlo of the SAME model the propagation linearizes: robots whose true
// wheel radii / tread differ from the nominal ones (fresh every step, or once
// per run) execute the commanded wheel speeds of the path; Euler integration
// P += tau f(theta, v, w) as in eq. (3), from an initial pose error drawn
// from N(0, diag(init^2)). Returns the covariance of the final position error
// (x, y).
Eigen::Matrix2d monteCarlo(const std::vector<TMotionStep>& steps, const TOdometryModel& m,
                           TErrorModel model, int runs, uint64_t seed,
                           const Eigen::Vector3d& init = Eigen::Vector3d::Zero()) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n01;
    auto draw = [&]() {
        TOdometryModel t = m;
        t.radiusL += m.sigmaRL * n01(rng);
        t.radiusR += m.sigmaRR * n01(rng);
        t.tread += m.sigmaT * n01(rng);
        return t;
    };
    // Nominal end pose.
    double nx = 0, ny = 0;
    {
        double th = steps.front().theta;
        for (const auto& k : steps) {
            double v, w;
            twistFromWheels(m, k.uL, k.uR, v, w);
            nx += k.tau * v * std::cos(th);
            ny += k.tau * v * std::sin(th);
            th += k.tau * w;
        }
    }
    Eigen::Matrix2d c = Eigen::Matrix2d::Zero();
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    std::vector<Eigen::Vector2d> errs;
    for (int r = 0; r < runs; r++) {
        TOdometryModel t = draw();
        double x = init[0] * n01(rng), y = init[1] * n01(rng),
               th = steps.front().theta + init[2] * n01(rng);
        for (const auto& k : steps) {
            if (model == TErrorModel::PerStep)
                t = draw();
            double v, w;
            twistFromWheels(t, k.uL, k.uR, v, w);
            x += k.tau * v * std::cos(th);
            y += k.tau * v * std::sin(th);
            th += k.tau * w;
        }
        errs.emplace_back(x - nx, y - ny);
        mean += errs.back() / runs;
    }
    for (const auto& e : errs)
        c += (e - mean) * (e - mean).transpose() / (runs - 1);
    return c;
}

Eigen::Matrix2d propagated(const std::vector<TMotionStep>& steps, const TOdometryModel& m,
                           TErrorModel model) {
    Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
    auto z = augmentedInitial(p, m);
    for (const auto& k : steps) {
        if (model == TErrorModel::PerStep)
            p = propagatePerStep(p, k.theta, k.uL, k.uR, k.tau, m);
        else
            z = propagateSystematic(z, k.theta, k.uL, k.uR, k.tau, m);
    }
    return model == TErrorModel::PerStep ? Eigen::Matrix2d(p.block<2, 2>(0, 0))
                                         : Eigen::Matrix2d(z.block<2, 2>(0, 0));
}

void expectClose(const Eigen::Matrix2d& mc, const Eigen::Matrix2d& pr, double tol) {
    // Diagonal entries relative; the off-diagonal relative to sqrt(sxx syy).
    EXPECT_NEAR(mc(0, 0) / pr(0, 0), 1.0, tol)
        << "sxx mc " << mc(0, 0) << " pr " << pr(0, 0);
    EXPECT_NEAR(mc(1, 1) / pr(1, 1), 1.0, tol)
        << "syy mc " << mc(1, 1) << " pr " << pr(1, 1);
    EXPECT_NEAR((mc(0, 1) - pr(0, 1)) / std::sqrt(pr(0, 0) * pr(1, 1)), 0.0, tol)
        << "sxy mc " << mc(0, 1) << " pr " << pr(0, 1);
}

// The paper's Fig. 2 case: 10 m straight, a 90 deg turn, 10 m straight; its robot
// (R = 63 mm, T = 399 mm, sigma_R = sigma_T = 1 mm), no initial error.
const std::vector<TPoint2D> kFig2 = {{0, 0}, {10, 0}, {10, 10}};
}  // namespace

TEST(OdometryCovariance, PerStepMatchesMonteCarloOnFig2Path) {
    TOdometryModel m;
    const auto steps = motionProfile(kFig2, m, 0.3, 0.5, 0.05);
    expectClose(monteCarlo(steps, m, TErrorModel::PerStep, 3000, 11),
                propagated(steps, m, TErrorModel::PerStep), 0.10);
}

TEST(OdometryCovariance, SystematicMatchesMonteCarloOnFig2Path) {
    // With the paper's 1 mm sigmas a constant radius error bends the path by
    // 0.56 rad (1 sigma) over 10 m: far outside the linear regime (next test).
    // A 0.05 mm calibration error (0.03 rad over 10 m) keeps it linear.
    TOdometryModel m;
    m.sigmaRL = m.sigmaRR = m.sigmaT = 0.00005;
    const auto steps = motionProfile(kFig2, m, 0.3, 0.5, 0.05);
    expectClose(monteCarlo(steps, m, TErrorModel::Systematic, 3000, 12),
                propagated(steps, m, TErrorModel::Systematic), 0.10);
}

TEST(OdometryCovariance, SystematicAtPaperSigmasIsOutsideTheLinearRegime) {
    // Measured, not hidden: with the paper's 1 mm sigmas a constant bias turns
    // the heading by 0.56 rad (1 sigma) over the first leg; sin and cos
    // saturate and first-order propagation (any EKF-style method, the
    // paper's included) misjudges the spread by far more than 10 %.
    TOdometryModel m;
    const auto steps = motionProfile(kFig2, m, 0.3, 0.5, 0.05);
    const auto mc = monteCarlo(steps, m, TErrorModel::Systematic, 3000, 13);
    const auto pr = propagated(steps, m, TErrorModel::Systematic);
    std::cout << "[systematic, 1 mm] Monte Carlo / linear: sxx " << mc(0, 0) / pr(0, 0)
              << ", syy " << mc(1, 1) / pr(1, 1) << "\n";
    EXPECT_TRUE(std::abs(mc(0, 0) / pr(0, 0) - 1) > 0.1 ||
                std::abs(mc(1, 1) / pr(1, 1) - 1) > 0.1);
}

TEST(OdometryCovariance, PerStepDependsOnTauSystematicDoesNot) {
    TOdometryModel m;
    const auto a = motionProfile(kFig2, m, 0.3, 0.5, 0.05),
               b = motionProfile(kFig2, m, 0.3, 0.5, 0.2);
    const double ps = propagated(a, m, TErrorModel::PerStep)(1, 1) /
                      propagated(b, m, TErrorModel::PerStep)(1, 1);
    const double sy = propagated(a, m, TErrorModel::Systematic)(1, 1) /
                      propagated(b, m, TErrorModel::Systematic)(1, 1);
    EXPECT_LT(ps, 0.5);          // 4x more steps of fresh error average out: ~1/4
    EXPECT_NEAR(sy, 1.0, 0.05);  // a bias is a bias, whatever the step
}

namespace {
// The position covariance (about the mean) that CPosePropagator gives at the
// end of the steps.
Eigen::Matrix2d propagatedBy(const std::vector<TMotionStep>& steps,
                             const TOdometryModel& m, TErrorModel model,
                             TPropagation prop, const Eigen::Vector3d& init) {
    const Eigen::Matrix3d p0 = init.cwiseAbs2().asDiagonal();
    CPosePropagator p(m, model, prop, p0, 0, 0, steps.front().theta, 1000, 3);
    for (const auto& k : steps) {
        double v, w;
        twistFromWheels(m, k.uL, k.uR, v, w);
        p.step(k.theta, k.uL, k.uR, k.tau, k.x, k.y, k.theta + w * k.tau);
    }
    return p.covariance().block<2, 2>(0, 0);
}
}  // namespace

// Linear propagation is far off outside its regime. The table of
// Monte Carlo / propagated ratios on the paper's Fig. 2 path (10 m, a 90 deg
// turn, 10 m; 0.3 m/s, 0.5 rad/s, tau 0.05 s) with the paper's robot and
// sigmas (1 mm wheel radii and tread, initial 1 mm, 1 mm, 0.1 rad), for both
// error models and every propagation; sxy as the ratio too (it is far from
// 0 at the end). The Monte Carlo is of the SAME model (20,000 robots).
// Tolerances: a sample variance of N = 20,000 Gaussian draws has a relative
// standard error sqrt(2/N) = 1 % (more for the bent, heavy-tailed systematic
// spread: allow 2 %), so 5 % is the reference's 3 sigma plus the 1-2 %
// measured error of the fifth-degree rule; `sampled` draws 1,000 robots of
// its own (4.5 % standard error per entry): 15 %. The third-degree unscented
// rule cannot follow the systematic model's bend (16-21 % measured): it is
// held to 25 % there and to 5 % under per_step, and is why cubature5 is the
// default.
TEST(OdometryCovariance, PropagationRatioTableOnFig2Path) {
    TOdometryModel m;
    const Eigen::Vector3d init(0.001, 0.001, 0.1);
    const auto steps = motionProfile(kFig2, m, 0.3, 0.5, 0.05);
    struct TProp {
        const char* name;
        TPropagation p;
    };
    const TProp props[] = {{"linear", TPropagation::Linear},
                           {"unscented", TPropagation::Unscented},
                           {"cubature5", TPropagation::Cubature5},
                           {"sampled", TPropagation::Sampled}};
    std::cout << "Monte Carlo / propagated, Fig. 2 path end (sxx, syy, sxy):\n";
    for (TErrorModel model : {TErrorModel::PerStep, TErrorModel::Systematic}) {
        const bool sys = model == TErrorModel::Systematic;
        const Eigen::Matrix2d mc =
            monteCarlo(steps, m, model, 20000, sys ? 21 : 22, init);
        for (const auto& pr : props) {
            const Eigen::Matrix2d c = propagatedBy(steps, m, model, pr.p, init);
            const double rx = mc(0, 0) / c(0, 0), ry = mc(1, 1) / c(1, 1),
                         rxy = mc(0, 1) / c(0, 1);
            std::printf("  %-10s %-9s  %6.3f  %6.3f  %6.3f\n",
                        sys ? "systematic" : "per_step", pr.name, rx, ry, rxy);
            double tol = 0;
            if (pr.p == TPropagation::Cubature5)
                tol = 0.05;
            else if (pr.p == TPropagation::Sampled)
                tol = 0.15;
            else if (pr.p == TPropagation::Unscented)
                tol = sys ? 0.25 : 0.05;
            if (tol > 0) {
                EXPECT_NEAR(rx, 1, tol) << pr.name;
                EXPECT_NEAR(ry, 1, tol) << pr.name;
                EXPECT_NEAR(rxy, 1, tol) << pr.name;
            }
            if (sys && pr.p == TPropagation::Linear) {  // measured, not hidden
                EXPECT_TRUE(std::abs(rx - 1) > 0.3 && std::abs(ry - 1) > 0.3);
            }
        }
    }
}

// Along the first leg the heading error of 0.1 rad shortens the run by
// L (1 - cos) (a second-order effect): linear propagation misses it and
// under-states the along-track variance (sxx) by two orders of magnitude
// (per_step; 5x systematic); the sigma points follow it. syy is lateral.
TEST(OdometryCovariance, AlongTrackSpreadOfAHeadingErrorAfterTheFirstLeg) {
    TOdometryModel m;
    const Eigen::Vector3d init(0.001, 0.001, 0.1);
    const auto all = motionProfile(kFig2, m, 0.3, 0.5, 0.05);
    std::vector<TMotionStep> leg;
    for (const auto& k : all)
        if (!k.turning && k.theta == all.front().theta)
            leg.push_back(k);
    std::cout
        << "Monte Carlo / propagated, end of the first leg (sxx along, syy across):\n";
    for (TErrorModel model : {TErrorModel::PerStep, TErrorModel::Systematic}) {
        const bool sys = model == TErrorModel::Systematic;
        const Eigen::Matrix2d mc = monteCarlo(leg, m, model, 20000, sys ? 24 : 23, init);
        for (const auto& [name, p] :
             {std::make_pair("linear", TPropagation::Linear),
              std::make_pair("unscented", TPropagation::Unscented),
              std::make_pair("cubature5", TPropagation::Cubature5),
              std::make_pair("sampled", TPropagation::Sampled)}) {
            const Eigen::Matrix2d c = propagatedBy(leg, m, model, p, init);
            std::printf("  %-10s %-9s  %8.3f  %6.3f\n", sys ? "systematic" : "per_step",
                        name, mc(0, 0) / c(0, 0), mc(1, 1) / c(1, 1));
            if (p == TPropagation::Linear) {
                EXPECT_GT(mc(0, 0) / c(0, 0), sys ? 3 : 50);
            }
            if (p == TPropagation::Cubature5) {
                EXPECT_NEAR(mc(0, 0) / c(0, 0), 1, 0.05);
                EXPECT_NEAR(mc(1, 1) / c(1, 1), 1, 0.05);
            }
        }
    }
}

// The rules integrate what they claim over N(0, I_n): weights sum to 1, the
// second moments are I, and the fifth-degree rule has E[xi_i^4] = 3,
// E[xi_i^2 xi_j^2] = 1.
TEST(OdometryCovariance, SigmaPointRulesMatchTheGaussianMoments) {
    for (int n : {3, 6}) {
        for (const auto& r : {unscentedPoints(n), cubature5Points(n)}) {
            double sw = 0;
            Eigen::MatrixXd m2 = Eigen::MatrixXd::Zero(n, n);
            double m4 = 0, m22 = 0;
            for (size_t j = 0; j < r.points.size(); j++) {
                sw += r.weights[j];
                m2 += r.weights[j] * r.points[j] * r.points[j].transpose();
                m4 += r.weights[j] * std::pow(r.points[j][0], 4);
                m22 += r.weights[j] * std::pow(r.points[j][0] * r.points[j][1], 2);
            }
            EXPECT_NEAR(sw, 1, 1e-12);
            EXPECT_NEAR((m2 - Eigen::MatrixXd::Identity(n, n)).norm(), 0, 1e-12);
            if (r.points.size() == size_t(2 * n * n + 1)) {
                EXPECT_NEAR(m4, 3, 1e-12);
                EXPECT_NEAR(m22, 1, 1e-12);
            }
        }
        EXPECT_EQ(cubature5Points(n).points.size(), size_t(2 * n * n + 1));
        EXPECT_EQ(unscentedPoints(n).points.size(), size_t(2 * n));
    }
}

// With no constant random variable to spread (no initial error) and the
// per_step model, the sigma points all drive the plan: the same covariance as
// the linear propagation (eq. 15) along it.
TEST(OdometryCovariance, SigmaPointsReduceToLinearWithoutInitialError) {
    TOdometryModel m;
    const auto steps = motionProfile(kFig2, m, 0.3, 0.5, 0.05);
    const Eigen::Matrix2d lin = propagatedBy(
        steps, m, TErrorModel::PerStep, TPropagation::Linear, Eigen::Vector3d::Zero());
    for (TPropagation p : {TPropagation::Unscented, TPropagation::Cubature5})
        EXPECT_LT(
            (propagatedBy(steps, m, TErrorModel::PerStep, p, Eigen::Vector3d::Zero()) -
             lin)
                .norm(),
            1e-9 * lin.norm());
}
