#include <risknav/common/config_read.h>
#include <risknav/sim/COdometrySim.h>

using namespace risknav::common;

namespace risknav::sim {
TWheelGeometry COdometrySim::nominalGeometry() const {
    return options.nominal();
}

TWheelGeometry COdometrySim::drawGeometry() {
    if (options.error_model == "none")
        return nominalGeometry();
    std::normal_distribution<double> n01(0.0, 1.0);
    TWheelGeometry g;
    g.radiusL = options.wheel_radius_l + options.sigma_wheel_radius_l * n01(m_rng);
    g.radiusR = options.wheel_radius_r + options.sigma_wheel_radius_r * n01(m_rng);
    g.tread = options.tread + options.sigma_tread * n01(m_rng);
    return g;
}

void COdometrySim::reset(const mrpt::math::TPose2D& start, uint64_t seed) {
    m_pose = start;
    m_rng.seed(seed);
    m_true = drawGeometry();
}

void COdometrySim::step(double vTrue, double wTrue, double dt) {
    if (options.error_model == "per_step")
        m_true = drawGeometry();
    double uL = 0, uR = 0, v = 0, w = 0;
    wheelsFromTwist(m_true, vTrue, wTrue, uL, uR);
    twistFromWheels(nominalGeometry(), uL, uR, v, w);
    m_pose = integrateTwist(m_pose, v, w, dt);
}

}  // namespace risknav::sim
