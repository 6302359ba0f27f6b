#pragma once
#include <risknav/common/diff_drive.h>

#include <mrpt/math/TPose2D.h>

namespace risknav::sim {
// The wheel kinematics live in common (the risk evaluator uses them too).
using common::TWheelGeometry;
using common::twistFromWheels;
using common::wheelsFromTwist;

/** Pose after moving with constant (v, omega) for dt, on the exact arc
 * (straight line when omega = 0). Heading wrapped to (-pi, pi]. */
mrpt::math::TPose2D integrateTwist(const mrpt::math::TPose2D& p, double v, double w,
                                   double dt);

}  // namespace risknav::sim
