#include <risknav/common/config_read.h>
#include <risknav/risk/TPropagationOptions.h>

using namespace risknav::common;

namespace risknav::risk {
namespace {
const std::vector<std::string> kPropagations = {"linear", "unscented", "cubature5",
                                                "sampled"};
}

TPropagation propagationFromName(const std::string& n) {
    if (n == "linear")
        return TPropagation::Linear;
    if (n == "unscented")
        return TPropagation::Unscented;
    if (n == "sampled")
        return TPropagation::Sampled;
    return TPropagation::Cubature5;
}

void TPropagationOptions::declare(Visitor& v) {
    v.number(tau, "tau", TRange::closed(0.001, 1, "s"), "propagation step of eq. (15)");
    v.number(speed, "speed", {0, 5, true, false, "m/s"}, "on straight legs");
    v.number(turn_rate_deg, "turn_rate_deg", {0, 720, true, false, "deg/s"},
             "turns in place at waypoints");
    // Bounded so that no covariance can overflow (sigmas near 1e154
    // would make D_max = inf and U = 0): 1 km, 10 m/s, a half turn (per second).
    v.number(init_sigma_x, "init_sigma_x", TRange::closed(0, 1000, "m"),
             "initial pose std. dev. (section 6.2: 1 mm)");
    v.number(init_sigma_y, "init_sigma_y", TRange::closed(0, 1000, "m"),
             "initial pose std. dev.");
    v.number(init_sigma_theta_deg, "init_sigma_theta_deg", TRange::closed(0, 180, "deg"),
             "initial heading std. dev. (section 6.2: 0.1 rad)");
    v.number(noise_sigma_x, "noise_sigma_x", TRange::closed(0, 10, "m/s"),
             "process noise n of eq. (3), x");
    v.number(noise_sigma_y, "noise_sigma_y", TRange::closed(0, 10, "m/s"),
             "process noise, y");
    v.number(noise_sigma_theta_deg, "noise_sigma_theta_deg",
             TRange::closed(0, 180, "deg/s"), "process noise, heading");
    v.choice(propagation, "propagation", kPropagations,
             "how the pose error is propagated along a route");
    v.integer(samples, "samples", TRange::closed(10, 100000),
              "robots of propagation = sampled");
}

TRiskOptions makeRiskOptions(const TOdometryOptions& odo, const TPropagationOptions& p,
                             double evalStep, uint64_t seed) {
    TRiskOptions o;
    auto& m = o.odometry;
    m.radiusL = odo.wheel_radius_l;
    m.radiusR = odo.wheel_radius_r;
    m.tread = odo.tread;
    const bool exact = odo.error_model == "none";
    m.sigmaRL = exact ? 0.0 : odo.sigma_wheel_radius_l;
    m.sigmaRR = exact ? 0.0 : odo.sigma_wheel_radius_r;
    m.sigmaT = exact ? 0.0 : odo.sigma_tread;
    // Degrees to radians as readDegrees() does: v * M_PI / 180.
    const double nt = p.noise_sigma_theta_deg * M_PI / 180.0;
    m.sigmaN = Eigen::Vector3d(p.noise_sigma_x * p.noise_sigma_x,
                               p.noise_sigma_y * p.noise_sigma_y, nt * nt)
                   .asDiagonal();
    o.model =
        odo.error_model == "systematic" ? TErrorModel::Systematic : TErrorModel::PerStep;
    o.tau = p.tau;
    o.speed = p.speed;
    o.turnRate = p.turn_rate_deg * M_PI / 180.0;
    const double st = p.init_sigma_theta_deg * M_PI / 180.0;
    o.sigmaP0 = Eigen::Vector3d(p.init_sigma_x * p.init_sigma_x,
                                p.init_sigma_y * p.init_sigma_y, st * st)
                    .asDiagonal();
    o.evalStep = evalStep;
    o.propagation = propagationFromName(p.propagation);
    o.samples = p.samples;
    o.seed = seed;
    return o;
}

}  // namespace risknav::risk
