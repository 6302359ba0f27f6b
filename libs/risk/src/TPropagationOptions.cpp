#include <risknav/common/config_read.h>
#include <risknav/risk/TPropagationOptions.h>

#include <algorithm>

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

void TPropagationOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                             const std::string& s) {
    section = s;
    tau = readDouble(c, s, "tau", tau);
    speed = readDouble(c, s, "speed", speed);
    turn_rate_deg = readDouble(c, s, "turn_rate_deg", turn_rate_deg);
    init_sigma_x = readDouble(c, s, "init_sigma_x", init_sigma_x);
    init_sigma_y = readDouble(c, s, "init_sigma_y", init_sigma_y);
    init_sigma_theta_deg = readDouble(c, s, "init_sigma_theta_deg", init_sigma_theta_deg);
    noise_sigma_x = readDouble(c, s, "noise_sigma_x", noise_sigma_x);
    noise_sigma_y = readDouble(c, s, "noise_sigma_y", noise_sigma_y);
    noise_sigma_theta_deg =
        readDouble(c, s, "noise_sigma_theta_deg", noise_sigma_theta_deg);
    propagation = readChoice(c, s, "propagation", propagation, kPropagations);
    samples = readInt(c, s, "samples", samples);
}

void TPropagationOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                           const std::string& s) const {
    writeKey(c, s, "tau", tau);
    writeKey(c, s, "speed", speed);
    writeKey(c, s, "turn_rate_deg", turn_rate_deg);
    writeKey(c, s, "init_sigma_x", init_sigma_x);
    writeKey(c, s, "init_sigma_y", init_sigma_y);
    writeKey(c, s, "init_sigma_theta_deg", init_sigma_theta_deg);
    writeKey(c, s, "noise_sigma_x", noise_sigma_x);
    writeKey(c, s, "noise_sigma_y", noise_sigma_y);
    writeKey(c, s, "noise_sigma_theta_deg", noise_sigma_theta_deg);
    writeKey(c, s, "propagation", propagation);
    writeKey(c, s, "samples", samples);
}

void TPropagationOptions::validate() const {
    const std::string& s = section;
    checkKey(s, "tau", tau, TRange::closed(0.001, 1, "s"));
    checkKey(s, "speed", speed, {0, 5, true, false, "m/s"});
    checkKey(s, "turn_rate_deg", turn_rate_deg, {0, 720, true, false, "deg/s"});
    // Bounded so that no covariance can overflow (sigmas near 1e154
    // would make D_max = inf and U = 0): 1 km, 10 m/s, a half turn (per second).
    checkKey(s, "init_sigma_x", init_sigma_x, TRange::closed(0, 1000, "m"));
    checkKey(s, "init_sigma_y", init_sigma_y, TRange::closed(0, 1000, "m"));
    checkKey(s, "init_sigma_theta_deg", init_sigma_theta_deg,
             TRange::closed(0, 180, "deg"));
    checkKey(s, "noise_sigma_x", noise_sigma_x, TRange::closed(0, 10, "m/s"));
    checkKey(s, "noise_sigma_y", noise_sigma_y, TRange::closed(0, 10, "m/s"));
    checkKey(s, "noise_sigma_theta_deg", noise_sigma_theta_deg,
             TRange::closed(0, 180, "deg/s"));
    checkRule(std::find(kPropagations.begin(), kPropagations.end(), propagation) !=
                  kPropagations.end(),
              s, "propagation", propagation,
              "must be one of: linear, unscented, cubature5, sampled");
    checkKey(s, "samples", samples, TRange::closed(10, 100000));
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
