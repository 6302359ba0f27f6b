#pragma once
#include <risknav/common/TOdometryOptions.h>
#include <risknav/sim/odometry_model.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/TPose2D.h>

#include <random>
#include <string>

namespace risknav::sim {
/** Wheel odometry of a differential-drive robot with imperfect knowledge of
 * its wheel radii and tread (the error model of Irie et al., PAPER_NOTES M2).
 *
 * The robot really moves with (v, omega). Its encoders measure the wheel
 * speeds that the TRUE geometry needs for that motion; the odometry turns
 * them back into (v, omega) with the NOMINAL geometry and integrates. The true
 * geometry is nominal + an error drawn from N(0, sigma):
 *  - systematic: drawn once per run (radius and tread errors are constant
 *    biases of a real robot; this is the physical model and the default);
 *  - per_step: drawn again every simulation step (the assumption behind the
 *    paper's eq. 15; its drift depends on the step length);
 *  - none: perfect odometry. */
class COdometrySim {
  public:
    /** The [Odometry] section: the shared robot schema. */
    common::TOdometryOptions options;

    /** Draws the systematic errors; call after setting options. */
    void reset(const mrpt::math::TPose2D& start, uint64_t seed);

    /** The robot moved with true (v, omega) for dt: updates the odometric pose. */
    void step(double vTrue, double wTrue, double dt);

    const mrpt::math::TPose2D& pose() const { return m_pose; }
    const TWheelGeometry& trueGeometry() const { return m_true; }
    TWheelGeometry nominalGeometry() const;

  private:
    TWheelGeometry drawGeometry();
    mrpt::math::TPose2D m_pose;
    TWheelGeometry m_true;
    std::mt19937_64 m_rng;
};

}  // namespace risknav::sim
