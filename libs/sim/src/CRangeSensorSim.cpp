#include <risknav/common/config_read.h>
#include <risknav/sim/CRangeSensorSim.h>

#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::sim {
void CRangeSensorSim::TOptions::declare(Visitor& v) {
    v.flag(enabled, "enabled", "the sensor scans");
    v.text(label, "label", true, "sensorLabel in the rawlog");
    // degrees as the file has them: the members hold degrees too
    v.number(fov_deg, "fov_deg", {0, 360, true, false, "deg"}, "field of view");
    v.integer(beams, "beams", TRange::closed(2, 10000), "rays per scan");
    v.number(max_range, "max_range", TRange::closed(0.1, 200, "m"), "maximum range");
    v.number(noise_std, "noise_std", TRange::closed(0, 1, "m"), "Gaussian range noise");
    v.number(dropout_probability, "dropout_probability", {0, 1, false, true, ""},
             "chance that a person / clutter disc is missed by a whole scan");
    v.integer(frame_decimation, "frame_decimation", TRange::closed(1, 1000),
              "a scan every N-th frame");
    v.number(x, "x", TRange::closed(-5, 5, "m"), "mounting position on the robot, ahead");
    v.number(y, "y", TRange::closed(-5, 5, "m"), "mounting position, to the left");
    v.number(z, "z", TRange::closed(-5, 5, "m"), "mounting height");
    v.number(yaw_deg, "yaw_deg", TRange::closed(-180, 180, "deg"), "mounting yaw");
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
