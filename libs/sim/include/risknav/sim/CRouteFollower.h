#pragma once
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <risknav/common/CDeclaredOptions.h>

#include <optional>
#include <string>
#include <vector>

namespace risknav::sim {
/** Drives a differential-drive robot along a waypoint route at a commanded
 * speed profile (one speed per route segment), for `laps` laps:
 *  - once: w0 .. wn;  loop: w0 .. wn w0, repeated;  back_and_forth: w0 .. wn .. w0,
 * repeated. A waypoint-seeking controller: turn in place when the heading error exceeds
 * turn_in_place_deg, otherwise proportional steering; it slows down so that
 * it can stop (with the robot's deceleration) at a sharp corner and at the end.
 * It uses the TRUE pose (a perfectly localized robot): odometry drift shows in
 * the logged odometry only. */
class CRouteFollower {
  public:
    /** [Route]: every key, its range and doc declared once, in declare(). */
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "Route"; }
        std::vector<double> waypoints;  ///< x0 y0 x1 y1 ... [m], at least 2 points
        double speed = 0.2;             ///< [m/s] commanded speed of every segment
        std::vector<double> speeds;     ///< [m/s] optional, one per segment of one pass
        int laps = 1;
        std::string mode = "back_and_forth";  ///< once | loop | back_and_forth
        double goal_tolerance = 0.1;          ///< [m]
        double heading_gain = 2.0;            ///< [1/s] omega = gain * heading error
        double turn_in_place_deg = 45;        ///< [deg]
        std::optional<double>
            start_heading_deg;  ///< [deg] default: towards the second waypoint

      protected:
        void declare(Visitor& v) override;
        void validateRules() const override;
    } options;

    /** Expands the route (laps, mode) and rewinds. */
    void reset();
    /** Desired (v, omega) at this pose, before safety stops and acceleration
     * limits. maxW [rad/s], decel [m/s^2] shape corner slow-down. */
    void compute(const mrpt::math::TPose2D& pose, double maxW, double decel, double& v,
                 double& w);
    bool finished() const { return m_idx >= m_points.size(); }
    /** The whole route as driven (all laps), and the speed of each leg i -> i+1. */
    const std::vector<mrpt::math::TPoint2D>& points() const { return m_points; }
    const std::vector<double>& legSpeeds() const { return m_legSpeed; }
    mrpt::math::TPose2D startPose() const;
    /** Waypoints of one pass, as points. */
    std::vector<mrpt::math::TPoint2D> waypoints() const;
    size_t targetIndex() const { return m_idx; }
    /** Length of the whole route (all laps) [m]. */
    double length() const;

  private:
    std::vector<mrpt::math::TPoint2D> m_points;
    std::vector<double> m_legSpeed;  // speed of leg (i-1 -> i), indexed by the target i
    size_t m_idx = 1;
};

}  // namespace risknav::sim
