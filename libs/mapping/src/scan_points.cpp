#include <risknav/mapping/scan_points.h>

#include <cmath>

namespace risknav::mapping {
double scanRayAngle(const mrpt::obs::CObservation2DRangeScan& scan, size_t i) {
    const size_t n = scan.getScanSize();
    const double a0 = -0.5 * scan.aperture, da = n > 1 ? scan.aperture / (n - 1) : 0.0;
    const double dir = scan.rightToLeft ? 1.0 : -1.0;
    return scan.sensorPose.yaw() + dir * (a0 + da * i);
}

std::vector<mrpt::math::TPoint2D> scanToRobotFrame(
    const mrpt::obs::CObservation2DRangeScan& scan) {
    std::vector<mrpt::math::TPoint2D> pts;
    const size_t n = scan.getScanSize();
    pts.reserve(n);
    const double sx = scan.sensorPose.x(), sy = scan.sensorPose.y();
    for (size_t i = 0; i < n; i++) {
        if (!scan.getScanRangeValidity(i))
            continue;
        const double r = scan.getScanRange(i), a = scanRayAngle(scan, i);
        pts.emplace_back(sx + r * std::cos(a), sy + r * std::sin(a));
    }
    return pts;
}

}  // namespace risknav::mapping
