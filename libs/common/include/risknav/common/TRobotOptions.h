#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <string>

namespace risknav::common {
/** The robot, the same [Robot] keys in every app's config (one schema, read by
 * this struct alone): body, speed and acceleration limits, and the detection
 * delay of the stopping distance d_stop(v) = t_delay v + v^2 / (2 decel)
 * (Choi et al. (002) eqs. 1-3, erratum in PAPER_NOTES M3). Every key, its
 * range and its doc are declared once, in declare(). */
struct TRobotOptions : public CDeclaredOptions {
    TRobotOptions() { section = "Robot"; }
    double radius = 0.25;      ///< [m] the robot is a disc
    double max_v = 0.8;        ///< [m/s] top speed
    double max_w_deg = 90;     ///< [deg/s] top turn rate
    double accel = 1.0;        ///< [m/s^2]
    double decel = 1.0;        ///< [m/s^2] braking
    double w_accel_deg = 180;  ///< [deg/s^2] turn acceleration
    double t_delay = 0.9;      ///< [s] maximum detection + reaction delay (002 Table 1)

  protected:
    void declare(Visitor& v) override;
};

}  // namespace risknav::common
