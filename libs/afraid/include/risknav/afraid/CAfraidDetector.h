#pragma once
#include <risknav/afraid/afraid_functions.h>
#include <risknav/common/CValidatedOptions.h>
#include <risknav/common/TRobotOptions.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <deque>
#include <string>

namespace risknav::afraid {
/** What the detector found in one frame. */
struct TAfraidStep {
    double speed = 0, dStop = 0;
    int obsCur = 1, obsPredict = 1;
    double actualArea = 0, expectedArea = 0, diff = 0;
    bool afraid = false;
    bool obstacleFound = false;
    double obstacleX = 0, obstacleY = 0;  ///< world position of the unexpected obstacle
};

/** Detects obstacles that appear abruptly (Choi, Chung, Song (002) section 2.4)
 * from a laser scan, the localized pose and the known map: the actual scan
 * gives A_area, a scan ray-cast on the map at the same pose gives E_area, and
 * eqs. (5), (6), (10), (11) decide. Sections [AfraidDetector] (options) and
 * [Robot] (robot: radius, and t_delay and decel of d_stop, eqs. 1-3). */
class CAfraidDetector {
  public:
    /** The [AfraidDetector] keys. */
    struct TOptions : public common::CValidatedOptions {
        double beta = 0.4;  ///< [m] marginal distance of eq. (5)
        double lateral_margin =
            0.1;  ///< [m] r of eqs. (5), (8) = robot radius + this (swept half-width)
        int foot_step = 5;  ///< cycles of eq. (6)
        double diff_threshold =
            5.0;  ///< [m] on diff = |E_area - A_area| (sum over 181 directions)
        int directions = 181;  ///< directions of eq. (9) over the forward half-plane
        double unexpected_margin =
            0.15;  ///< [m] a ray shorter than the map's by this is an unmapped obstacle

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                              const std::string& section) const override;
        void validate() const override;
    };

    TOptions options;             ///< [AfraidDetector]
    common::TRobotOptions robot;  ///< [Robot]: radius, t_delay, decel

    /** Loads [AfraidDetector] and [Robot] (each validated). */
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c);
    /** Writes [AfraidDetector] and [Robot]. */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** Both options structs' validate(). Throws CConfigKeyError. */
    void validate() const;

    /** r of eqs. (5) and (8): the half-width of the corridor the robot sweeps,
     * robot radius + lateral_margin [m]. */
    double halfWidth() const { return robot.radius + options.lateral_margin; }

    void reset() { m_history.clear(); }

    /** One frame: the scan, the localized pose, the robot's speed [m/s]. */
    TAfraidStep step(const mrpt::obs::CObservation2DRangeScan& scan,
                     const mrpt::math::TPose2D& pose, double speed,
                     const mrpt::maps::COccupancyGridMap2D& map);

  private:
    std::deque<int> m_history;
};

}  // namespace risknav::afraid
