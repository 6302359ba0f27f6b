#include <risknav/speed/speed_rules.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace risknav::speed {
std::vector<size_t> safeSpeedsByGap(const std::vector<double>& costToGo,
                                    double threshold) {
    std::vector<size_t> order(costToGo.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return costToGo[a] < costToGo[b]; });
    size_t keep = order.size();
    for (size_t k = 1; k < order.size(); k++) {
        const double lo = costToGo[order[k - 1]], hi = costToGo[order[k]];
        if (std::isinf(hi) && !std::isinf(lo)) {
            keep = k;
            break;
        }
        if (hi - lo > threshold) {
            keep = k;
            break;
        }
    }
    std::vector<size_t> safe(order.begin(), order.begin() + long(keep));
    std::sort(safe.begin(), safe.end());
    return safe;
}

bool undecidedRuleHolds(double d, double v, double cycleTime, int necessaryObservations) {
    if (v <= 0)
        return true;
    if (std::isinf(d))
        return true;
    // d / (v T) >= N, tolerant of the rounding in d / (v T) (1.65 / 0.33)
    return d / (v * cycleTime) >= necessaryObservations - 1e-9;
}
}  // namespace risknav::speed
