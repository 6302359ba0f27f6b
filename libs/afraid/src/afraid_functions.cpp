#include <risknav/afraid/afraid_functions.h>

#include <algorithm>
#include <cmath>

namespace risknav::afraid {
int obsCur(const std::vector<mrpt::math::TPoint2D>& pts, double dStop, double beta,
           double halfWidth) {
    for (const auto& p : pts)
        if (p.x > 0 && std::abs(p.y) <= halfWidth && p.x < dStop + beta)
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

double nonBlockedArea(const std::vector<mrpt::math::TPoint2D>& pts, double dStop,
                      double beta, double r, int nDirections) {
    // Obstacles the robot could meet: within dist_stop + beta.
    std::vector<std::pair<double, double>> near;  // (d, bearing)
    for (const auto& p : pts) {
        const double d = std::hypot(p.x, p.y);
        if (d <= dStop + beta && p.x > -r)
            near.emplace_back(d, std::atan2(p.y, p.x));
    }
    double area = 0;
    for (int i = 0; i < nDirections; i++) {
        const double th = -M_PI / 2 + M_PI * i / std::max(1, nDirections - 1);
        double reach = dStop;
        for (const auto& [d, b] : near) {
            const double dth = th - b;
            if (std::cos(dth) <= 0)
                continue;  // behind this direction
            const double lateral = d * std::abs(std::sin(dth));
            if (lateral <= r)
                reach = std::min(reach, lateral);
        }
        area += reach;
    }
    return area;
}

bool afraidFlag(int obsCurNow, int obsPredictNow, double diff, double diffThreshold) {
    return obsCurNow == 0 && obsPredictNow == 1 && diff > diffThreshold;
}

}  // namespace risknav::afraid
