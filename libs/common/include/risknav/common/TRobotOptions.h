#pragma once
#include <risknav/common/CValidatedOptions.h>

#include <string>

namespace risknav::common {
/** The robot, the same [Robot] keys in every app's config (one schema, read by
 * this struct alone): body, speed and acceleration limits, and the detection
 * delay of the stopping distance d_stop(v) = t_delay v + v^2 / (2 decel)
 * (Choi et al. (002) eqs. 1-3, erratum in PAPER_NOTES M3). */
struct TRobotOptions : public CValidatedOptions {
    double radius = 0.25;      ///< [m] the robot is a disc
    double max_v = 0.8;        ///< [m/s] top speed
    double max_w_deg = 90;     ///< [deg/s] top turn rate
    double accel = 1.0;        ///< [m/s^2]
    double decel = 1.0;        ///< [m/s^2] braking
    double w_accel_deg = 180;  ///< [deg/s^2] turn acceleration
    double t_delay = 0.9;      ///< [s] maximum detection + reaction delay (002 Table 1)

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                          const std::string& section) const override;
    void validate() const override;
};

}  // namespace risknav::common
