#include <risknav/viewpoint/viewpoint_greedy.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

using mrpt::math::TPoint2D;

namespace risknav::viewpoint {
std::vector<TPathSample> samplePath(
    const std::vector<TPoint2D>& path, double step,
    const std::function<double(double, double)>& allowed) {
    if (!(step > 0))
        throw std::invalid_argument("samplePath: step must be > 0");
    std::vector<TPathSample> out;
    if (path.empty())
        return out;
    double s0 = 0;
    for (size_t i = 0; i + 1 < path.size(); i++) {
        const TPoint2D& a = path[i];
        const TPoint2D& b = path[i + 1];
        const double L = std::hypot(b.x - a.x, b.y - a.y);
        const double h = std::atan2(b.y - a.y, b.x - a.x);
        const int n = std::max(1, int(std::ceil(L / step)));
        for (int k = 0; k < n; k++) {
            const double f = double(k) / n;
            const double x = a.x + f * (b.x - a.x), y = a.y + f * (b.y - a.y);
            out.push_back({s0 + f * L, x, y, h, allowed(x, y)});
        }
        s0 += L;
    }
    const TPoint2D& e = path.back();
    const double h = out.empty() ? 0 : out.back().heading;
    out.push_back({s0, e.x, e.y, h, allowed(e.x, e.y)});
    return out;
}

double reachFrom(const std::vector<TPathSample>& s, size_t i, double ePos, double dPhi,
                 double dr) {
    const double k = dr + 2 * std::sin(std::min(dPhi, M_PI) / 2);  // error per metre
    auto slack = [&](size_t j) { return s[j].allowed - (ePos + k * (s[j].s - s[i].s)); };
    if (slack(i) < 0)
        return -1;
    for (size_t j = i + 1; j < s.size(); j++) {
        const double g = slack(j);
        if (g < 0) {
            const double g0 = slack(j - 1);
            const double m0 = s[j - 1].s - s[i].s, m1 = s[j].s - s[i].s;
            return m0 + (m1 - m0) * g0 / (g0 - g);
        }
    }
    return s.back().s - s[i].s;
}

TGreedyResult planViewpointsGreedy(const std::vector<TPathSample>& s, double ePos0,
                                   double dPhi0, double dr,
                                   const std::function<double(size_t)>& bestReach,
                                   bool prune) {
    TGreedyResult r;
    if (s.empty())
        return r;
    const double L = s.back().s;
    const double eps = 1e-9;
    const double m0 = reachFrom(s, 0, ePos0, dPhi0, dr);
    if (m0 < 0)
        return r;  // the start itself is not safe with the start error
    size_t cur = 0;
    double reach = m0;
    r.reach = reach;
    while (reach < L - eps) {
        // Candidates: the samples after the current viewpoint up to the reach.
        std::vector<std::pair<double, size_t>> cand;  // (bound, index)
        for (size_t i = cur + 1; i < s.size() && s[i].s <= reach + eps; i++) {
            const double ub = prune ? s[i].s + std::max(0.0, reachFrom(s, i, 0, 0, dr))
                                    : std::numeric_limits<double>::infinity();
            cand.push_back({ub, i});
        }
        std::stable_sort(cand.begin(), cand.end(), [](const auto& a, const auto& b) {
            return a.first != b.first ? a.first > b.first : a.second > b.second;
        });
        double best = -std::numeric_limits<double>::infinity();
        size_t bi = 0;
        for (const auto& [ub, i] : cand) {
            if (prune && ub < best - eps)
                break;
            const double m = bestReach(i);
            r.evaluations++;
            if (m < 0)
                continue;
            const double v = s[i].s + m;
            if (v > best + eps || (std::abs(v - best) <= eps && i > bi)) {
                best = v;
                bi = i;
            }
        }
        if (!(best > reach + eps)) {
            r.reach = reach;
            return r;  // no observation gets further: infeasible here
        }
        r.viewpoints.push_back(bi);
        cur = bi;
        reach = best;
        r.reach = std::min(reach, L);
    }
    r.feasible = true;
    r.reach = L;
    return r;
}

}  // namespace risknav::viewpoint
