#pragma once
#include <risknav/afraid/afraid_functions.h>
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/TRobotOptions.h>
#include <risknav/mapping/CDistanceField.h>

#include <mrpt/math/CMatrixFixed.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <deque>
#include <string>

namespace risknav::afraid {
/** What the detector found in one frame. */
struct TAfraidStep {
    double speed = 0;  ///< [m/s] the speed d_stop uses (the highest of the recent frames)
    double dStop = 0;
    TCollisionArea area;
    int obsCur = 1, obsPredict = 1;
    double actualArea = 0, expectedArea = 0;
    double diff = 0;        ///< eq. (10) as a fraction of the collision-possible area
    size_t explained = 0;   ///< points the map explains within the pose uncertainty
    size_t unexpected = 0;  ///< points in the collision area the map does not explain
    bool afraid = false;
    bool obstacleFound = false;
    double obstacleX = 0, obstacleY = 0;  ///< world position of the unexpected obstacle
    double obstacleAlong = 0;  ///< [m] its distance ahead of the robot's centre
};

/** Detects obstacles that appear abruptly (Choi, Chung, Song (002) section 2.4)
 * from a laser scan, the localized pose and the known map: the actual scan
 * gives A_area, a scan ray-cast on the map at the same pose gives E_area, and
 * eqs. (5), (6), (10), (11) decide. Sections [AfraidDetector] (options) and
 * [Robot] (robot: radius, and t_delay and decel of d_stop, eqs. 1-3).
 *
 * Beyond the paper, so that it holds on worlds it was not tuned on:
 *  - one collision area for eqs. 5 and 8 (TCollisionArea);
 *  - d_stop uses the highest speed of the last foot_step frames in which the
 *    robot headed the same way (within 15 deg): a robot that brakes for a
 *    person does not shrink its collision area to nothing while the person
 *    steps in (and a standing robot keeps radius + beta), but one that stops
 *    and turns in place does not sweep its old area over what it turns to;
 *  - eq. (6) tracks the unexpected obstacles (obs_cur = 0 AND diff >
 *    threshold), not every obstacle in the collision area (see step());
 *  - localization error is not an obstacle: a scan point that lies closer to
 *    the map's obstacles than the pose uncertainty explains (unexpected_margin
 *    + explain_sigmas x the pose's position sigma + range x its heading sigma)
 *    is the map's obstacle seen from a slightly wrong pose, and counts in
 *    A_area as the map predicts it (its ray takes the expected range), so it
 *    cannot make diff. */
class CAfraidDetector {
  public:
    /** The [AfraidDetector] keys. */
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "AfraidDetector"; }
        double beta = 0.4;  ///< [m] marginal distance of eq. (5)
        /** [m] the collision area's half-width = robot radius + this. */
        double lateral_margin = 0.1;
        int foot_step = 5;  ///< cycles of eq. (6)
        /** eq. (11) threshold on diff, a fraction of the collision-possible area. */
        double diff_threshold = 0.05;
        int directions = 181;  ///< directions of eq. (9) over the forward half-plane
        /** [m] a scan point this close to a map obstacle is the map's obstacle
         * even with a perfect pose (cell size, sensor noise). */
        double unexpected_margin = 0.15;
        /** Pose standard deviations that still explain a point's offset. */
        double explain_sigmas = 3.0;

      protected:
        void declare(Visitor& v) override;
    };

    TOptions options;             ///< [AfraidDetector]
    common::TRobotOptions robot;  ///< [Robot]: radius, t_delay, decel

    /** Loads [AfraidDetector] and [Robot] (each validated). */
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c);
    /** Writes [AfraidDetector] and [Robot]. */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** Both options structs' validate(). Throws CConfigKeyError. */
    void validate() const;

    /** The half-width of the corridor the robot sweeps (the collision area of
     * eqs. 5 and 8), robot radius + lateral_margin [m]. */
    double halfWidth() const { return robot.radius + options.lateral_margin; }

    void reset() {
        m_history.clear();
        m_speeds.clear();
    }

    /** One frame: the scan, the localized pose and its covariance (x, y, phi;
     * zero: a perfect pose), the robot's speed [m/s], the map and its
     * distance field (the same obstacle rule). */
    TAfraidStep step(const mrpt::obs::CObservation2DRangeScan& scan,
                     const mrpt::math::TPose2D& pose,
                     const mrpt::math::CMatrixDouble33& cov, double speed,
                     const mrpt::maps::COccupancyGridMap2D& map,
                     const mapping::CDistanceField& field);

  private:
    std::deque<int> m_history;
    std::deque<std::pair<double, double>> m_speeds;  // (speed, heading) of recent frames
};

}  // namespace risknav::afraid
