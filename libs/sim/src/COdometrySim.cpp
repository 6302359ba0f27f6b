#include <risknav/common/config_read.h>
#include <risknav/sim/COdometrySim.h>

using namespace risknav::common;

namespace risknav::sim {
void COdometrySim::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                                const std::string& s) {
    wheel_radius =
        readDouble(c, s, "wheel_radius", wheel_radius, TRange::closed(0.005, 2, "m"));
    tread = readDouble(c, s, "tread", tread, TRange::closed(0.02, 5, "m"));
    sigma_wheel_radius = readDouble(c, s, "sigma_wheel_radius", sigma_wheel_radius,
                                    TRange::nonNegative("m"));
    sigma_tread = readDouble(c, s, "sigma_tread", sigma_tread, TRange::nonNegative("m"));
    error_model =
        readChoice(c, s, "error_model", error_model, {"systematic", "per_step", "none"});
}

void COdometrySim::TOptions::validate() const {
    // A 3-sigma error must not flip the sign of a radius or of the tread.
    if (3 * sigma_wheel_radius >= wheel_radius)
        throw CConfigKeyError("Odometry", "sigma_wheel_radius",
                              std::to_string(sigma_wheel_radius),
                              "must be < wheel_radius / 3");
    if (3 * sigma_tread >= tread)
        throw CConfigKeyError("Odometry", "sigma_tread", std::to_string(sigma_tread),
                              "must be < tread / 3");
}

TWheelGeometry COdometrySim::nominalGeometry() const {
    return {options.wheel_radius, options.wheel_radius, options.tread};
}

TWheelGeometry COdometrySim::drawGeometry() {
    if (options.error_model == "none")
        return nominalGeometry();
    std::normal_distribution<double> n01(0.0, 1.0);
    TWheelGeometry g;
    g.radiusL = options.wheel_radius + options.sigma_wheel_radius * n01(m_rng);
    g.radiusR = options.wheel_radius + options.sigma_wheel_radius * n01(m_rng);
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
