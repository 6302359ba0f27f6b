#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/CSpeedLimiter.h>

#include <string>

namespace risknav::sim {
/** Sensed obstacles against the stopping distance: the robot may not drive on
 * at speed v while a sensed point lies in its swept corridor (half-width
 * radius + lateral_margin) closer than d_stop(v) + margin ahead of its front,
 * with d_stop(v) = t_delay v + v^2 / (2 decel) (Choi et al. (002) eqs. 1-3,
 * PAPER_NOTES M3 erratum). Its limit is 0 (stop) or the desired speed. The
 * simulator's safety stop; a CSpeedLimiter plugin. Section [CStoppingDistanceLimiter] in
 * risknav-simulate. */
class CStoppingDistanceLimiter : public common::CSpeedLimiter {
    DEFINE_MRPT_OBJECT(CStoppingDistanceLimiter, risknav::sim)
  public:
    /** The section read (its errors name it): [CStoppingDistanceLimiter] in
     * every app (and in MRPT's engine INI). Every key, its range and its doc
     * are declared once, in declare(). */
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "CStoppingDistanceLimiter"; }
        bool enabled = true;
        double margin = 0.1;          ///< [m] beta: added to d_stop
        double lateral_margin = 0.1;  ///< [m] swept corridor half-width = radius + this
        /** Which swept corridor: "straight" (along the heading, eq. 4 as the
         * paper), "path" (along the controller's path when it gives one) or
         * "both" (the nearer of the two: a robot that lags its planned turn
         * sweeps between them). */
        std::string corridor = "both";

      protected:
        void declare(Visitor& v) override;
    } options;

    /** Whether moving at speed v [m/s] is blocked by a point of the scan: the
     * collision condition |x_robot - x_obstacle| < d_stop(v) of Choi et al.
     * (002) eq. (4), measured from the robot's front, plus the margin. */
    bool blocked(const mrpt::obs::CObservation2DRangeScan& scan, double v,
                 const common::TRobotOptions& robot) const;
    /** The same for obstacle points already in the robot frame. */
    bool blocked(const std::vector<mrpt::math::TPoint2D>& robotFramePoints, double v,
                 const common::TRobotOptions& robot) const;

    /** Free distance [m] ahead: from the robot's front, less the margin, to
     * the nearest point inside the swept corridor (+inf when none). The
     * limit is the highest speed whose d_stop fits in it (maxStoppableSpeed),
     * so a speed is limited exactly when blocked() says it is blocked. */
    double freeDistance(const std::vector<mrpt::math::TPoint2D>& robotFramePoints,
                        const common::TRobotOptions& robot) const;

    /** The same along a curved path (robot frame, with the distance along it
     * to each pose): the distance to the first pose whose disc of radius +
     * lateral_margin holds a sensed point not already within that disc of
     * the robot, less the margin (+inf when none). Used when the limiter is
     * given the controller's path (MRPT's PTG trajectory). */
    double freeDistanceAlong(const std::vector<mrpt::math::TPoint2D>& robotFramePoints,
                             const std::vector<mrpt::math::TPose2D>& path,
                             const std::vector<double>& distance,
                             const common::TRobotOptions& robot) const;

    void loadConfig(const mrpt::config::CConfigFileBase& c,
                    const std::string& section) override;
    void saveConfig(mrpt::config::CConfigFileBase& c,
                    const std::string& section) const override;

  protected:
    common::TSpeedLimit impl_limit(const common::TSpeedLimitInput& in) const override;
};

/** Registers libs/sim's MRPT classes (and those of the libraries below it)
 * with MRPT's class registry, so that they can be created by name. Call it
 * once before creating plugins by name: MRPT's automatic registration runs
 * from static initializers that a static link may drop. Idempotent. */
void registerAllClasses_sim();

}  // namespace risknav::sim
