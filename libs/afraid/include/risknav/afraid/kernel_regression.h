#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <string>
#include <vector>

namespace risknav::afraid {
/** Gaussian-kernel regression with square loss (Choi, Chung, Song (002)
 * section 2.5: empirical risk minimization in the RKHS of a Gaussian kernel =
 * kernel ridge regression): f(x) = sum_i alpha_i k(x, x_i) with
 * (K + lambda I) alpha = y, k(a, b) = exp(-|a - b|^2 / (2 h^2)).
 *
 * Beyond the paper, for maps of 2000 x 2000 cells: the kernel is cut at
 * `cutoff` bandwidths (exp(-8) = 3e-4 at 4 h), which makes K sparse; the
 * system is solved by conjugate gradients on the sparse SPD matrix (no dense
 * n x n inverse), and f is evaluated only within the cutoff of a sample.
 *
 * Config keys kernel_bandwidth, kernel_lambda, kernel_cutoff in the host
 * section (e.g. [AfraidLearn]); the CG tolerance is not configurable. */
struct TKrrOptions : public common::CDeclaredOptions {
    /** The host section (for messages) until loaded from one. */
    TKrrOptions() { section = "AfraidLearn"; }

    double bandwidth = 0.5;  ///< h [m]
    double lambda = 0.5;     ///< ridge regularization
    double cutoff = 4.0;     ///< kernel support, in bandwidths
    double tolerance = 1e-10;

    /** Public: the host sections' structs declare these keys among theirs
     * (CAfraidSpeedLimiter::TOptions). */
    void declare(Visitor& v) override;
};

struct TKrrSample {
    double x = 0, y = 0, target = 0;
};

/** alpha of the truncated-kernel ridge regression (sparse CG). */
std::vector<double> krrFit(const std::vector<TKrrSample>& s, const TKrrOptions& o);
/** The same with a dense matrix and a direct solve (the reference, small n only). */
std::vector<double> krrFitDense(const std::vector<TKrrSample>& s, const TKrrOptions& o);
/** f at one point. */
double krrPredict(const std::vector<TKrrSample>& s, const std::vector<double>& alpha,
                  const TKrrOptions& o, double x, double y);
/** f on a grid (row-major, cell centres xmin + (cx + 0.5) res ...). */
std::vector<float> krrPredictGrid(const std::vector<TKrrSample>& s,
                                  const std::vector<double>& alpha, const TKrrOptions& o,
                                  double xmin, double ymin, double res, int sx, int sy);

}  // namespace risknav::afraid
