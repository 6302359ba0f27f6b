#pragma once
#include <risknav/common/CValidatedOptions.h>
#include <risknav/common/TRobotOptions.h>

#include <mrpt/obs/CObservation2DRangeScan.h>

#include <string>

namespace risknav::sim {
/** The simulated robot's safety stop: it must not drive on while a sensed
 * point lies in its swept corridor (half-width radius + lateral_margin) closer
 * than the stopping distance d_stop(v) + margin ahead of its front, with
 * d_stop(v) = t_delay v + v^2 / (2 decel) (Choi et al. (002) eqs. 1-3,
 * PAPER_NOTES M3 erratum). Section [StoppingRule]. */
class CStoppingRule {
  public:
    struct TOptions : public common::CValidatedOptions {
        bool enabled = true;
        double margin = 0.1;          ///< [m] beta: added to d_stop
        double lateral_margin = 0.1;  ///< [m] swept corridor half-width = radius + this

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                              const std::string& s) const override;
        void validate() const override;
    } options;

    /** Whether moving at speed v [m/s] is blocked by a point of the scan. */
    bool blocked(const mrpt::obs::CObservation2DRangeScan& scan, double v,
                 const common::TRobotOptions& robot) const;
};

}  // namespace risknav::sim
