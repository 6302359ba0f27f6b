#include <risknav/afraid/kernel_regression.h>
#include <risknav/common/config_read.h>

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>

#include <cmath>
#include <unordered_map>

using namespace risknav::common;

namespace risknav::afraid {
void TKrrOptions::declare(Visitor& v) {
    v.number(bandwidth, "kernel_bandwidth", TRange::closed(0.01, 100, "m"),
             "Gaussian kernel h");
    v.number(lambda, "kernel_lambda", TRange{0, 1e6, true, false, ""},
             "ridge regularization");
    v.number(cutoff, "kernel_cutoff", TRange::closed(1, 10, "bandwidths"),
             "the kernel is cut here (sparse solve)");
}

namespace {
// Samples bucketed by cutoff-sized cells, for neighbour queries.
struct TBuckets {
    double size;
    std::unordered_map<long long, std::vector<size_t>> cells;
    static long long key(long long i, long long j) {
        // Shift the bits as unsigned: a negative i shifted left is undefined.
        return static_cast<long long>(
            (static_cast<unsigned long long>(i) << 32) ^
            (static_cast<unsigned long long>(j) & 0xffffffffULL));
    }
    TBuckets(const std::vector<TKrrSample>& s, double sz) : size(sz) {
        for (size_t k = 0; k < s.size(); k++)
            cells[key(std::llround(std::floor(s[k].x / size)),
                      std::llround(std::floor(s[k].y / size)))]
                .push_back(k);
    }
    template <class F>
    void near(double x, double y, F&& f) const {
        const long long i0 = std::llround(std::floor(x / size)),
                        j0 = std::llround(std::floor(y / size));
        for (long long i = i0 - 1; i <= i0 + 1; i++)
            for (long long j = j0 - 1; j <= j0 + 1; j++) {
                const auto it = cells.find(key(i, j));
                if (it != cells.end())
                    for (size_t k : it->second)
                        f(k);
            }
    }
};

double kernel(double d2, const TKrrOptions& o) {
    const double c = o.cutoff * o.bandwidth;
    return d2 > c * c ? 0.0 : std::exp(-d2 / (2 * o.bandwidth * o.bandwidth));
}
}  // namespace

std::vector<double> krrFit(const std::vector<TKrrSample>& s, const TKrrOptions& o) {
    const size_t n = s.size();
    if (n == 0)
        return {};
    const TBuckets b(s, o.cutoff * o.bandwidth);
    std::vector<Eigen::Triplet<double>> t;
    for (size_t i = 0; i < n; i++)
        b.near(s[i].x, s[i].y, [&](size_t j) {
            const double k =
                kernel(std::pow(s[i].x - s[j].x, 2) + std::pow(s[i].y - s[j].y, 2), o);
            if (k > 0)
                t.emplace_back(int(i), int(j), k + (i == j ? o.lambda : 0.0));
        });
    Eigen::SparseMatrix<double> A(static_cast<int>(n), static_cast<int>(n));
    A.setFromTriplets(t.begin(), t.end());
    Eigen::VectorXd y(static_cast<int>(n));
    for (size_t i = 0; i < n; i++)
        y(int(i)) = s[i].target;
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(o.tolerance);
    cg.setMaxIterations(int(10 * n + 100));
    cg.compute(A);
    const Eigen::VectorXd a = cg.solve(y);
    return std::vector<double>(a.data(), a.data() + n);
}

std::vector<double> krrFitDense(const std::vector<TKrrSample>& s, const TKrrOptions& o) {
    const int n = int(s.size());
    Eigen::MatrixXd A(n, n);
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; i++) {
        y(i) = s[size_t(i)].target;
        for (int j = 0; j < n; j++)
            A(i, j) = kernel(std::pow(s[size_t(i)].x - s[size_t(j)].x, 2) +
                                 std::pow(s[size_t(i)].y - s[size_t(j)].y, 2),
                             o) +
                      (i == j ? o.lambda : 0.0);
    }
    const Eigen::VectorXd a = A.ldlt().solve(y);
    return std::vector<double>(a.data(), a.data() + n);
}

double krrPredict(const std::vector<TKrrSample>& s, const std::vector<double>& alpha,
                  const TKrrOptions& o, double x, double y) {
    double f = 0;
    for (size_t i = 0; i < s.size(); i++)
        f += alpha[i] * kernel(std::pow(x - s[i].x, 2) + std::pow(y - s[i].y, 2), o);
    return f;
}

std::vector<float> krrPredictGrid(const std::vector<TKrrSample>& s,
                                  const std::vector<double>& alpha, const TKrrOptions& o,
                                  double xmin, double ymin, double res, int sx, int sy) {
    std::vector<float> g(size_t(sx) * sy, 0.f);
    const int rc = int(std::ceil(o.cutoff * o.bandwidth / res));
    for (size_t i = 0; i < s.size(); i++) {
        if (alpha[i] == 0)
            continue;
        const int cx0 = int(std::floor((s[i].x - xmin) / res)),
                  cy0 = int(std::floor((s[i].y - ymin) / res));
        for (int cy = std::max(0, cy0 - rc); cy <= std::min(sy - 1, cy0 + rc); cy++)
            for (int cx = std::max(0, cx0 - rc); cx <= std::min(sx - 1, cx0 + rc); cx++) {
                const double x = xmin + (cx + 0.5) * res, y = ymin + (cy + 0.5) * res;
                g[size_t(cy) * sx + cx] +=
                    float(alpha[i] *
                          kernel(std::pow(x - s[i].x, 2) + std::pow(y - s[i].y, 2), o));
            }
    }
    return g;
}

}  // namespace risknav::afraid
