#include <risknav/sim/odometry_model.h>

#include <mrpt/math/wrap2pi.h>

#include <cmath>

namespace risknav::sim {
mrpt::math::TPose2D integrateTwist(const mrpt::math::TPose2D& p, double v, double w,
                                   double dt) {
    mrpt::math::TPose2D q = p;
    const double dphi = w * dt;
    if (std::abs(dphi) < 1e-9) {
        q.x += v * dt * std::cos(p.phi + 0.5 * dphi);
        q.y += v * dt * std::sin(p.phi + 0.5 * dphi);
    } else {
        const double r = v / w;
        q.x += r * (std::sin(p.phi + dphi) - std::sin(p.phi));
        q.y += -r * (std::cos(p.phi + dphi) - std::cos(p.phi));
    }
    q.phi = mrpt::math::wrapToPi(p.phi + dphi);
    return q;
}

}  // namespace risknav::sim
