#include <risknav/sim/range_geometry.h>

#include <cmath>

namespace risknav::sim {
double rayDiscDistance(double ox, double oy, double dx, double dy, const TDisc& c) {
    const double fx = ox - c.x, fy = oy - c.y;
    const double b = fx * dx + fy * dy;  // half the linear coefficient (|d| = 1)
    const double cc = fx * fx + fy * fy - c.r * c.r;
    if (cc <= 0)
        return 0.0;
    const double disc = b * b - cc;
    if (disc < 0)
        return std::numeric_limits<double>::infinity();
    const double t = -b - std::sqrt(disc);
    return t >= 0 ? t : std::numeric_limits<double>::infinity();
}

}  // namespace risknav::sim
