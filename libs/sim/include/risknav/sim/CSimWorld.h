#pragma once
#include <risknav/common/TRobotOptions.h>
#include <risknav/common/grid_io.h>
#include <risknav/mapping/CDistanceField.h>
#include <risknav/mapping/TObstacleRule.h>
#include <risknav/sim/CAgentsSim.h>
#include <risknav/sim/CDiffDriveVehicle.h>
#include <risknav/sim/COdometrySim.h>
#include <risknav/sim/CRangeSensorSim.h>
#include <risknav/sim/CRayCastMap.h>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/math/TTwist2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace risknav::sim {
/** A steppable world: a static occupancy map, the people and clutter the map
 * does not show, and a differential-drive robot (MRPT's
 * CVehicleSimul_DiffDriven, stepped for exactly dt: CDiffDriveVehicle) with
 * acceleration limits, wheel odometry with the
 * errors of Irie et al. and range sensors. A controller (route follower,
 * speed controller, MRPT's reactive navigator through CSimRobotInterface)
 * commands a velocity, step() advances physics, odometry and people, sense()
 * returns this instant's scans.
 *
 * The obstacle rule ([World]) decides for the collisions, the clearances and
 * the range sensors alike which cells are walls (CDistanceField and
 * CRayCastMap, both through TObstacleRule::isObstacle): with
 * unknown_is_obstacle an unknown cell echoes and is a collision, without it
 * it is neither.
 *
 * Sections: [World] (map source + obstacle rule), [Robot], [Odometry],
 * [Laser], [RangeSensor2], [DoorPedestrianN], [CorridorWalkerN], [ClutterN];
 * keys documented in config/risknav-simulate.ini. */
class CSimWorld {
  public:
    common::TMapSourceOptions mapSource;  ///< [World]
    mapping::TObstacleRule
        obstacleRule;  ///< [World]: collisions, clearance, route checks, sensors
    common::TRobotOptions robot;  ///< [Robot]
    COdometrySim odometry;        ///< [Odometry]
    CRangeSensorSim laser;        ///< [Laser]: the main sensor, every sense()
    CRangeSensorSim range2;       ///< [RangeSensor2]: optional, decimated
    CAgentsSim agents;

    /** The scans of one instant; range2 is null when it is off or not due. */
    struct TScans {
        mrpt::obs::CObservation2DRangeScan::Ptr laser, range2;
    };

    CSimWorld();

    /** Loads and validates the sections above and the map. Does not check for
     * unknown sections or keys (the app does, knowing its other sections). */
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c);
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** The people's paths and doors and the clutter against the map (after
     * loadFromConfigFile()): a path point or door end off the map, a path
     * segment through a map obstacle, clutter off the map or inside an
     * obstacle. Throws CBadInputError naming the file, section and key. Every
     * app that steps the world calls it. */
    void checkAgentsAgainstMap(const mrpt::config::CConfigFileBase& c) const;
    /** The first of the half-cell samples of segment a-b (a and b included)
     * where `bad` holds, or nullopt. */
    std::optional<mrpt::math::TPoint2D> firstSampleWhere(
        const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
        const std::function<bool(const mrpt::math::TPoint2D&)>& bad) const;
    /** Ranges a sense() gives on average: the laser's beams plus the second
     * sensor's per its frame decimation (when enabled); what bounds a rawlog. */
    double rangesPerFrame() const;
    /** (x, y) within the map's bounds. */
    bool onMap(double x, double y) const;

    /** Where the robot disc at a point would be in collision. */
    struct TPlacement {
        /** What it hits: "" (nothing), "the map" (off it or on an obstacle) or
         * a clutter section, "[ClutterN]". */
        std::string with;
        /** The reason after the point, e.g. "is inside an obstacle (clearance
         * 0.20 m < robot radius 0.25 m)"; "" when free. */
        std::string why;
        bool free() const { return with.empty(); }
    };
    /** The robot disc at (x, y) against the map and the clutter, in metres:
     * the exact distance to the obstacle cells' squares (pointClearance(),
     * what collisions are counted with) against the robot radius. The one
     * start check of every app that steps the world (the distance field's
     * whole cells let a start 0.20 m from a wall pass for a 0.25 m robot,
     * which then collided at t = 0). */
    TPlacement placement(double x, double y) const;

    /** Sets the map directly (from code); validates the options. */
    void setMap(const mrpt::maps::COccupancyGridMap2D& grid);

    /** Puts the robot at `start` at rest, draws the odometry errors and
     * restarts people and sensor noise from independent streams of `seed`.
     * startTime: UNIX time [s] of time() = 0 (scan timestamps). */
    void reset(const mrpt::math::TPose2D& start, uint64_t seed, double startTime = 0);

    /** The commanded velocity [m/s, rad/s], clamped to max_v / max_w; the
     * robot follows it within its acceleration limits. */
    void command(double v, double w);
    /** Advances the world by dt [s] under the current command: the speed
     * moves towards the command within the acceleration limits, then the
     * robot drives that twist for exactly dt. */
    void step(double dt);
    void step(double v, double w, double dt) {
        command(v, w);
        step(dt);
    }
    /** The scans of this instant (laser; range2 every frame_decimation-th call). */
    TScans sense();

    double time() const { return m_base + m_count * m_dt; }
    mrpt::Clock::time_point timestamp() const;
    mrpt::math::TPose2D truePose() const { return m_vehicle.getCurrentGTPose(); }
    mrpt::math::TPose2D odometricPose() const { return odometry.pose(); }
    /** Current forward speed and turn rate (after the acceleration limits). */
    double speed() const { return m_v; }
    /** The commanded forward speed (after clamping to max_v). */
    double commandedSpeed() const { return m_vCmd; }
    /** The commanded turn rate (after clamping to max_w). */
    double commandedTurnRate() const { return m_wCmd; }
    double turnRate() const { return m_w; }
    /** Global-frame velocity of the robot (MRPT convention). */
    mrpt::math::TTwist2D velocity() const { return m_vehicle.getCurrentGTVel(); }

    const mrpt::maps::COccupancyGridMap2D& grid() const { return m_grid; }
    const risknav::mapping::CDistanceField& distanceField() const { return m_field; }
    /** The map the range sensors cast their rays on (the same obstacles). */
    const CRayCastMap& rayCastMap() const { return m_rayMap; }
    /** Distance [m] from (x, y) to the nearest map obstacle (0 inside one or off the
     * map). */
    double clearance(double x, double y) const { return m_field.clearanceAt(x, y); }
    /** The same, exact from the point to the obstacle cells' squares near it
     * (CDistanceField::pointClearance): what collisions are counted with. */
    double pointClearance(double x, double y) const {
        return m_field.pointClearance(x, y, robot.radius + 0.3);
    }
    /** People events since reset (emerge, spawn, leave, give_up). */
    const std::vector<TAgentEvent>& agentEvents() const { return m_agentEvents; }
    size_t range2Scans() const { return m_range2Scans; }
    CDiffDriveVehicle& vehicle() { return m_vehicle; }

  private:
    void buildField();
    mrpt::maps::COccupancyGridMap2D m_grid;
    risknav::mapping::CDistanceField m_field;
    CRayCastMap m_rayMap;
    CDiffDriveVehicle m_vehicle;
    std::mt19937_64 m_rngLaser, m_rngRange2;
    std::vector<TAgentEvent> m_agentEvents;
    double m_v = 0, m_w = 0, m_vCmd = 0, m_wCmd = 0;
    double m_startTime = 0;
    // time() = m_base + m_count * m_dt: equal to k * dt for k steps of one dt
    // (bit for bit, as the rawlog timestamps have always been).
    double m_base = 0, m_dt = 0;
    long m_count = 0;
    size_t m_senses = 0, m_range2Scans = 0;
};

}  // namespace risknav::sim
