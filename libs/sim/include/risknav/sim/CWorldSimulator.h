#pragma once
#include <risknav/common/CAppRunner.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/grid_io.h>
#include <risknav/sim/CAgentsSim.h>
#include <risknav/sim/COdometrySim.h>
#include <risknav/sim/CRangeSensorSim.h>
#include <risknav/sim/CRouteFollower.h>

#include <mrpt/maps/COccupancyGridMap2D.h>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace risknav::sim {
/** A world (static map + people + clutter) and a differential-drive robot
 * that drives a route through it, logged as an MRPT rawlog.
 *
 * Config sections: [Simulation] [World] [Robot] [Odometry] [Route] [Laser]
 * [RangeSensor2] [DoorPedestrianN] [CorridorWalkerN] [ClutterN]; every key is
 * documented in config/risknav-simulate.ini. */
class CWorldSimulator {
  public:
    struct TSimulationOptions {
        double sim_dt = 0.05;  ///< [s] physics / control step
        double frame_rate_hz =
            5.0;  ///< [Hz] one rawlog frame (odometry + scans) per period
        double duration_max =
            3600;  ///< [s] stop (status "timeout") if the route is not done
        uint64_t seed = 1;
        double start_time =
            1.6e9;  ///< [s] UNIX time of the first frame (fixed: reproducible logs)
        double obstacle_threshold = 0.5;  ///< cells with P(free) below this are obstacles
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s);
        void validate() const;
    };
    struct TRobotOptions {
        double radius = 0.25;         ///< [m] robot disc
        double max_v = 0.8;           ///< [m/s]
        double max_w_deg = 90;        ///< [deg/s]
        double accel = 1.0;           ///< [m/s^2]
        double decel = 1.0;           ///< [m/s^2] braking
        double w_accel_deg = 180;     ///< [deg/s^2]
        bool stop_enabled = true;     ///< stop for obstacles within the stopping distance
        double stop_t_delay = 0.9;    ///< [s] detection delay of d_stop (PAPER_NOTES M3)
        double stop_margin = 0.1;     ///< [m] beta: extra distance added to d_stop
        double lateral_margin = 0.1;  ///< [m] swept corridor half-width = radius + this
        double near_miss_distance =
            0.2;  ///< [m] gap below which a pass counts as near miss
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s);
        void validate() const {}
    };

    TSimulationOptions simulation;
    TRobotOptions robot;
    common::TMapSourceOptions world;
    COdometrySim odometry;
    CRouteFollower route;
    CRangeSensorSim laser, range2;
    CAgentsSim agents;

    CWorldSimulator();

    /** Loads every section, the map, and checks the route and agents against
     * the map (start inside an obstacle, a route through a wall, paths off
     * the map): throws CBadInputError before any output is written. */
    void loadFromConfigFile(const common::CIniConfig& c,
                            std::optional<uint64_t> seedOverride);

    /** Runs to the end of the route (or duration_max) and writes
     * simulation.rawlog, groundtruth.txt, odometry.txt, agent_events.csv,
     * safety_events.csv, map.gridmap.gz, world.png into `out` (staged;
     * the caller commits). Returns the summary (without the app header). */
    nlohmann::json run(common::COutputDir& out, bool quiet);

    const mrpt::maps::COccupancyGridMap2D& grid() const { return m_grid; }
    /** Distance [m] from (x, y) to the nearest obstacle cell (0 inside one or off the
     * map). */
    double clearance(double x, double y) const;

  private:
    void checkAgainstMap(const common::CIniConfig& c) const;
    mrpt::maps::COccupancyGridMap2D m_grid;
    cv::Mat m_clearance;  // CV_32F, row = cy, metres
};

/** The risknav-simulate app body (apps/ only parse the CLI). */
void runSimulateApp(const common::TAppContext& ctx);

}  // namespace risknav::sim
