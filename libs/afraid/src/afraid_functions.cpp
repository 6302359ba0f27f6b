#include <risknav/afraid/afraid_functions.h>

#include <algorithm>
#include <cmath>

namespace risknav::afraid {
int obsCur(const std::vector<mrpt::math::TPoint2D>& pts, const TCollisionArea& area) {
    for (const auto& p : pts)
        if (area.contains(p))
            return 0;
    return 1;
}

int obsPredict(const std::deque<int>& history, size_t footStep) {
    int prod = 1;
    size_t n = 0;
    for (auto it = history.rbegin(); it != history.rend() && n < footStep; ++it, ++n)
        prod *= *it;
    return prod;
}

double nonBlockedArea(const std::vector<mrpt::math::TPoint2D>& pts,
                      const TCollisionArea& area, int nDirections) {
    std::vector<std::pair<double, double>> inside;  // (d, bearing)
    for (const auto& p : pts)
        if (area.contains(p))
            inside.emplace_back(std::hypot(p.x, p.y), std::atan2(p.y, p.x));
    const int n = std::max(1, nDirections);
    if (inside.empty())
        return n * area.length;
    double sum = 0;
    for (int i = 0; i < n; i++) {
        const double th = n > 1 ? -M_PI / 2 + M_PI * i / (n - 1) : 0.0;
        double reach = area.length;
        for (const auto& [d, b] : inside) {
            const double c = std::cos(th - b);
            if (c <= 0)
                continue;  // behind this direction
            if (d * std::abs(std::sin(th - b)) <= area.halfWidth)
                reach = std::min(reach, d * c);
        }
        sum += reach;
    }
    return sum;
}

double areaDifference(double expectedArea, double actualArea, const TCollisionArea& area,
                      int nDirections) {
    const double whole = std::max(1, nDirections) * area.length;
    return whole > 0 ? std::abs(expectedArea - actualArea) / whole : 0.0;
}

bool afraidFlag(int obsCurNow, int obsPredictNow, double diff, double diffThreshold) {
    return obsCurNow == 0 && obsPredictNow == 1 && diff > diffThreshold;
}

}  // namespace risknav::afraid
