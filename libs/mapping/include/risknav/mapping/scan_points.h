#pragma once
#include <mrpt/math/TPoint2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <vector>

namespace risknav::mapping {
/** The valid returns of a 2D range scan as points in the robot frame: the
 * sensor's pose on the robot (x, y, yaw) applied, and the ray order honoured
 * (rightToLeft: ray i at -aperture/2 + i * aperture / (N - 1); otherwise the
 * mirror image). Invalid rays are skipped. */
std::vector<mrpt::math::TPoint2D> scanToRobotFrame(
    const mrpt::obs::CObservation2DRangeScan& scan);

/** Robot-frame angle of ray i of a scan (the same convention). */
double scanRayAngle(const mrpt::obs::CObservation2DRangeScan& scan, size_t i);

}  // namespace risknav::mapping
