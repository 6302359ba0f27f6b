#include <risknav/nav/escape_heading.h>

#include <mrpt/math/wrap2pi.h>

#include <cmath>

namespace risknav::nav {
std::optional<double> escapeHeading(const std::vector<mrpt::math::TPoint2D>& near,
                                    double preferred, double extra, double maxOff) {
    if (near.empty())
        return std::nullopt;
    const double half = M_PI / 2 + extra;  // each point forbids |h - bearing| <= half
    std::vector<double> bearings;
    bearings.reserve(near.size());
    for (const auto& p : near)
        bearings.push_back(std::atan2(p.y, p.x));
    auto admissible = [&](double h) {
        for (const double b : bearings)
            if (std::abs(mrpt::math::wrapToPi(h - b)) <= half)
                return false;
        return true;
    };
    // The admissible set is the complement of a union of arcs: its point
    // nearest `preferred` is `preferred` itself or just beyond an arc's end.
    constexpr double kBeyond = 1e-6;  // [rad] off the closed arc's end
    std::optional<double> best;
    double bestOff = 0;
    auto consider = [&](double h) {
        h = mrpt::math::wrapToPi(h);
        const double off = std::abs(mrpt::math::wrapToPi(h - preferred));
        if (off <= maxOff && (!best || off < bestOff) && admissible(h))
            best = h, bestOff = off;
    };
    consider(preferred);
    for (const double b : bearings) {
        consider(b + half + kBeyond);
        consider(b - half - kBeyond);
    }
    return best;
}
}  // namespace risknav::nav
