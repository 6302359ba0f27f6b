#include <risknav/common/config_read.h>
#include <risknav/sim/CRangeSensorSim.h>

#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::sim {
void CRangeSensorSim::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                                   const std::string& s) {
    section = s;
    enabled = readBool(c, s, "enabled", enabled);
    label = readString(c, s, "label", label);
    fov_deg = readDouble(c, s, "fov_deg", fov_deg);
    beams = readInt(c, s, "beams", beams);
    max_range = readDouble(c, s, "max_range", max_range);
    noise_std = readDouble(c, s, "noise_std", noise_std);
    dropout_probability = readDouble(c, s, "dropout_probability", dropout_probability);
    frame_decimation = readInt(c, s, "frame_decimation", frame_decimation);
    x = readDouble(c, s, "x", x);
    y = readDouble(c, s, "y", y);
    z = readDouble(c, s, "z", z);
    yaw_deg = readDouble(c, s, "yaw_deg", yaw_deg);
}

void CRangeSensorSim::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                 const std::string& s) const {
    writeKey(c, s, "enabled", enabled);
    writeKey(c, s, "label", label);
    writeKey(c, s, "fov_deg", fov_deg);
    writeKey(c, s, "beams", beams);
    writeKey(c, s, "max_range", max_range);
    writeKey(c, s, "noise_std", noise_std);
    writeKey(c, s, "dropout_probability", dropout_probability);
    writeKey(c, s, "frame_decimation", frame_decimation);
    writeKey(c, s, "x", x);
    writeKey(c, s, "y", y);
    writeKey(c, s, "z", z);
    writeKey(c, s, "yaw_deg", yaw_deg);
}

void CRangeSensorSim::TOptions::validate() const {
    const std::string& s = section;
    checkRule(!label.empty(), s, "label", label, "must not be empty");
    checkKey(s, "fov_deg", fov_deg, {0, 360, true, false, "deg"});
    checkKey(s, "beams", beams, TRange::closed(2, 10000));
    checkKey(s, "max_range", max_range, TRange::closed(0.1, 200, "m"));
    checkKey(s, "noise_std", noise_std, TRange::closed(0, 1, "m"));
    checkKey(s, "dropout_probability", dropout_probability, {0, 1, false, true, ""});
    checkKey(s, "frame_decimation", frame_decimation, TRange::closed(1, 1000));
    checkKey(s, "x", x, TRange::closed(-5, 5, "m"));
    checkKey(s, "y", y, TRange::closed(-5, 5, "m"));
    checkKey(s, "z", z, TRange::closed(-5, 5, "m"));
    checkKey(s, "yaw_deg", yaw_deg, TRange::closed(-180, 180, "deg"));
}

mrpt::obs::CObservation2DRangeScan::Ptr CRangeSensorSim::simulate(
    const CRayCastMap& map, const mrpt::math::TPose2D& robot,
    const std::vector<TDisc>& discs, mrpt::Clock::time_point t,
    std::mt19937_64& rng) const {
    const auto& o = options;
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    scan->sensorLabel = o.label;
    scan->timestamp = t;
    scan->aperture = static_cast<float>(o.fov_deg * M_PI / 180.0);
    scan->maxRange = static_cast<float>(o.max_range);
    scan->rightToLeft = true;
    scan->stdError = static_cast<float>(std::max(o.noise_std, 1e-3));
    scan->sensorPose =
        mrpt::poses::CPose3D(o.x, o.y, o.z, o.yaw_deg * M_PI / 180.0, 0, 0);
    // Static map, noise-free: noise is added once below, from our own seeded
    // generator (laserScanSimulator would draw from MRPT's global one). The
    // map's cells are 0 or 1 (CRayCastMap): the 0.5 decides nothing.
    map.grid().laserScanSimulator(*scan, mrpt::poses::CPose2D(robot), 0.5f,
                                  static_cast<size_t>(o.beams), 0.0f);

    // Which discs this scan sees (per-object dropout).
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::vector<const TDisc*> visible;
    for (const auto& d : discs)
        if (o.dropout_probability <= 0 || u01(rng) >= o.dropout_probability)
            visible.push_back(&d);

    const mrpt::poses::CPose2D sensor =
        mrpt::poses::CPose2D(robot) +
        mrpt::poses::CPose2D(o.x, o.y, o.yaw_deg * M_PI / 180.0);
    const size_t n = scan->getScanSize();
    const double a0 = -0.5 * scan->aperture, da = n > 1 ? scan->aperture / (n - 1) : 0.0;
    std::normal_distribution<double> noise(0.0, 1.0);
    for (size_t i = 0; i < n; i++) {
        double r = scan->getScanRangeValidity(i)
                       ? scan->getScanRange(i)
                       : std::numeric_limits<double>::infinity();
        if (!visible.empty()) {
            const double ang = sensor.phi() + a0 + da * i;
            const double dx = std::cos(ang), dy = std::sin(ang);
            for (const TDisc* d : visible)
                r = std::min(r, rayDiscDistance(sensor.x(), sensor.y(), dx, dy, *d));
        }
        if (std::isfinite(r) && o.noise_std > 0)
            r += o.noise_std * noise(rng);
        const bool valid = std::isfinite(r) && r > 0 && r < o.max_range;
        scan->setScanRange(i, static_cast<float>(valid ? r : o.max_range));
        scan->setScanRangeValidity(i, valid);
    }
    return scan;
}

}  // namespace risknav::sim
