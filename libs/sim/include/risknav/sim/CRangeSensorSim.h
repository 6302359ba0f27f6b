#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/sim/CRayCastMap.h>
#include <risknav/sim/range_geometry.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <random>
#include <string>
#include <vector>

namespace risknav::sim {
/** A planar range sensor: rays cast on the static map's obstacles as the
 * obstacle rule classifies them (CRayCastMap: the cells the collisions count,
 * unknown cells by unknown_is_obstacle) with MRPT's
 * COccupancyGridMap2D::laserScanSimulator, and against disc obstacles (people,
 * clutter) that the map does not contain; Gaussian range noise; optional
 * per-object dropout (each disc independently missed in a whole scan, as a
 * stereo or sonar sensor misses objects). Output: a CObservation2DRangeScan
 * (MRPT ray order: -fov/2 .. +fov/2, right to left). */
class CRangeSensorSim {
  public:
    /** [Laser], [RangeSensor2]: every key, its range and its doc are
     * declared once, in declare(). */
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "Laser"; }
        bool enabled = true;
        std::string label = "LASER";
        double fov_deg = 180;            ///< [deg] (0, 360]
        int beams = 181;                 ///< rays per scan
        double max_range = 8.0;          ///< [m]
        double noise_std = 0.01;         ///< [m] range noise (1 sigma)
        double dropout_probability = 0;  ///< [0, 1) chance a disc is missed in a scan
        int frame_decimation =
            1;  ///< a scan every N-th frame (frames follow the main laser)
        double x = 0.2, y = 0.0, z = 0.3;  ///< [m] mounting position on the robot
        double yaw_deg = 0;                ///< [deg] mounting yaw

      protected:
        void declare(Visitor& v) override;
    } options;

    /** One scan from the robot pose at timestamp t. */
    mrpt::obs::CObservation2DRangeScan::Ptr simulate(const CRayCastMap& map,
                                                     const mrpt::math::TPose2D& robot,
                                                     const std::vector<TDisc>& discs,
                                                     mrpt::Clock::time_point t,
                                                     std::mt19937_64& rng) const;
};

}  // namespace risknav::sim
