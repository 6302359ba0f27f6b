#pragma once
#include <risknav/afraid/afraid_functions.h>

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
 * eqs. (5), (6), (10), (11) decide. Section [AfraidDetector]. */
class CAfraidDetector {
  public:
    struct TOptions {
        double t_delay = 0.9;  ///< [s] detection delay of d_stop (Table 1)
        double decel = 1.0;    ///< [m/s^2] braking deceleration of d_stop
        double beta = 0.4;     ///< [m] marginal distance of eq. (5)
        double half_width =
            0.35;  ///< [m] r: half-width of the swept corridor (robot radius + margin)
        int foot_step = 5;  ///< cycles of eq. (6)
        double diff_threshold =
            5.0;  ///< [m] on diff = |E_area - A_area| (sum over 181 directions)
        int directions = 181;  ///< directions of eq. (9) over the forward half-plane
        double unexpected_margin =
            0.15;  ///< [m] a ray shorter than the map's by this is an unmapped obstacle
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s);
        void validate() const {}
    } options;

    void reset() { m_history.clear(); }

    /** One frame: the scan, the localized pose, the robot's speed [m/s]. */
    TAfraidStep step(const mrpt::obs::CObservation2DRangeScan& scan,
                     const mrpt::math::TPose2D& pose, double speed,
                     const mrpt::maps::COccupancyGridMap2D& map);

    /** Points of a scan in the robot frame (valid rays only). */
    static std::vector<TPoint> robotFramePoints(
        const mrpt::obs::CObservation2DRangeScan& scan);

  private:
    std::deque<int> m_history;
};

}  // namespace risknav::afraid
