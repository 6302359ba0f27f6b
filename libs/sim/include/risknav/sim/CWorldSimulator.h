#pragma once
#include <risknav/common/CAppRunner.h>
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/COutputDir.h>
#include <risknav/sim/CRouteFollower.h>
#include <risknav/sim/CSafetyMonitor.h>
#include <risknav/sim/CSimWorld.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace risknav::sim {
/** risknav-simulate on the closed loop (CClosedLoop): a robot follows a route
 * (CRouteFollower) through a steppable world (CSimWorld) under the stopping
 * rule (CStoppingDistanceLimiter); every frame period the world's scans and
 * the odometry increment go to an MRPT rawlog; the loop's CSafetyMonitor
 * counts collisions and near misses.
 *
 * Config sections: [Simulation] [Route] [CStoppingDistanceLimiter] and the world's
 * ([World] [Robot] [Odometry] [Laser] [RangeSensor2] [DoorPedestrianN] [CorridorWalkerN]
 * [ClutterN]); every key is documented in config/risknav-simulate.ini. */
class CWorldSimulator {
  public:
    /** [Simulation]: every key, its range and its doc are declared once, in
     * declare(). */
    struct TSimulationOptions : public common::CDeclaredOptions {
        TSimulationOptions() { section = "Simulation"; }
        double sim_dt = 0.05;  ///< [s] physics / control step
        double frame_rate_hz =
            5.0;  ///< [Hz] one rawlog frame (odometry + scans) per period
        double duration_max =
            3600;  ///< [s] stop (status "timeout") if the route is not done
        uint64_t seed = 1;
        double start_time =
            1.6e9;  ///< [s] UNIX time of the first frame (reproducible logs)
        double near_miss_distance =
            0.2;  ///< [m] gap below which a pass counts as near miss
        /** The collision-possible area in which a door pedestrian's entry is
         * logged (enter_corridor, "relevant" for the afraid detector): beta
         * [m] beyond d_stop ahead of the robot's front, and lateral_margin [m]
         * beyond its radius to each side (Choi et al. (002) eq. 5 and Fig. 1;
         * the afraid detector's defaults). */
        double relevance_beta = 0.4;
        double relevance_lateral_margin = 0.1;

      protected:
        void declare(Visitor& v) override;
        /** The frame period is a whole multiple of sim_dt. */
        void validateRules() const override;
    };

    TSimulationOptions simulation;
    CSimWorld world;
    CRouteFollower route;
    CStoppingDistanceLimiter stopRule;

    /** Loads every section, the map, and checks the route and agents against
     * the map (start inside an obstacle, a route through a wall, paths off
     * the map): throws CBadInputError before any output is written. */
    void loadFromConfigFile(const common::CIniConfig& c,
                            std::optional<uint64_t> seedOverride);
    /** Every key of every section with the value this run uses. */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;

    /** Runs to the end of the route (or duration_max) and writes
     * simulation.rawlog, groundtruth.txt, odometry.txt, agent_events.csv,
     * safety_events.csv, map.gridmap.gz, world.png into `out` (staged;
     * the caller commits). Returns the summary (without the app header). */
    nlohmann::json run(common::COutputDir& out, bool quiet);

    const mrpt::maps::COccupancyGridMap2D& grid() const { return world.grid(); }

  private:
    struct TRun;  // the state of one run (files, tracks, counters)
    void checkAgainstMap(const common::CIniConfig& c) const;
    void recordFrame(TRun& r);
    void controlStep(TRun& r);
    void writeEventTables(const TRun& r, common::COutputDir& out) const;
    void drawWorld(const TRun& r, const std::string& path) const;
    nlohmann::json summary(const TRun& r, common::COutputDir& out) const;
};

/** The risknav-simulate app body (apps/ only parse the CLI). */
void runSimulateApp(const common::TAppContext& ctx);

}  // namespace risknav::sim
