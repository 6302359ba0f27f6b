#include <risknav/nav/plan_follow.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace risknav::nav {
using mrpt::math::TPoint2D;

double arcClearance(const std::vector<TPoint2D>& obstacles, double v, double w,
                    double distance) {
    double least = std::numeric_limits<double>::infinity();
    const int n = std::max(0, int(std::ceil(distance / 0.02)));
    for (int k = 0; k <= n; k++) {
        // the pose after s metres of the arc (v > 0), robot frame at the start
        const double s = n == 0 ? 0.0 : distance * k / n;
        double x = s, y = 0, phi = 0;
        if (std::abs(w) > 1e-9 && v > 1e-9) {
            const double r = v / w;
            phi = s / r;
            x = r * std::sin(phi);
            y = r * (1 - std::cos(phi));
        }
        for (const auto& q : obstacles)
            least = std::min(least, std::hypot(q.x - x, q.y - y));
    }
    return least;
}

TFollowCommand planFollowCommand(const mrpt::math::TPose2D& pose,
                                 const std::vector<TPoint2D>& ahead,
                                 const std::vector<TPoint2D>& obstacles, double clearance,
                                 double vMax, double wMax, double lookahead,
                                 double horizon, double floor) {
    TFollowCommand out;
    if (ahead.empty() || !(vMax > 0) || !(wMax > 0)) {
        out.blocked = true, out.what = "blocked";
        return out;
    }
    // the aim: lookahead metres along the plan (its end when shorter)
    TPoint2D aim = ahead.back();
    double along = 0;
    for (size_t k = 1; k < ahead.size(); k++) {
        const double seg =
            std::hypot(ahead[k].x - ahead[k - 1].x, ahead[k].y - ahead[k - 1].y);
        if (along + seg >= lookahead) {
            const double f = seg > 0 ? (lookahead - along) / seg : 0.0;
            aim = TPoint2D(ahead[k - 1].x + f * (ahead[k].x - ahead[k - 1].x),
                           ahead[k - 1].y + f * (ahead[k].y - ahead[k - 1].y));
            break;
        }
        along += seg;
    }
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    const double dx = aim.x - pose.x, dy = aim.y - pose.y;
    const double lx = c * dx + s * dy, ly = -s * dx + c * dy;
    const double alpha = std::atan2(ly, lx);
    constexpr double kTurnAbove = 30 * M_PI / 180;
    if (std::abs(alpha) > kTurnAbove) {
        out.w = (alpha > 0 ? 1 : -1) * wMax;
        out.what = "turn";
        return out;
    }
    // pure pursuit: the arc through the aim, curvature 2 ly / d^2
    const double d2 = lx * lx + ly * ly;
    const double kappa = d2 > 1e-12 ? 2 * ly / d2 : 0.0;
    double v = vMax * (1 - 0.5 * std::abs(alpha) / kTurnAbove);
    if (std::abs(kappa) * v > wMax)
        v = wMax / std::abs(kappa);
    // a robot already nearer than `clearance` (stopped there by its
    // engine) may move on if it gets no nearer (5 mm of the scan's noise
    // allowed), but not nearer than `floor`; one already nearer than that
    // gets no nearer at all (the 5 mm, cycle after cycle, had let it creep
    // onto a post)
    const double start = arcClearance(obstacles, 0, 0, 0);
    const double need =
        start >= floor ? std::max(floor, std::min(clearance, start - 0.005)) : start;
    for (; v >= vMax / 8 - 1e-12; v /= 2) {
        if (arcClearance(obstacles, v, v * kappa, v * horizon + 0.05) >= need) {
            out.v = v, out.w = v * kappa, out.what = "drive";
            return out;
        }
    }
    // every arc starts along the heading: one that leads toward an obstacle
    // before it bends away is turned out of first (a disc turns in place
    // without nearing anything), down to 3 deg off the aim
    if (std::abs(alpha) > 3 * M_PI / 180) {
        out.w =
            (alpha > 0 ? 1 : -1) * std::min(wMax, std::max(0.2 * wMax, std::abs(alpha)));
        out.what = "turn";
        return out;
    }
    out.blocked = true, out.what = "blocked";
    return out;
}
}  // namespace risknav::nav
