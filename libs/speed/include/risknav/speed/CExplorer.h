#pragma once
#include <risknav/common/CIniConfig.h>
#include <risknav/mapping/CLocalProbGrid.h>
#include <risknav/sim/CSafetyMonitor.h>
#include <risknav/sim/CSimWorld.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>
#include <risknav/speed/CAdaptiveSpeedController.h>
#include <risknav/speed/CAdaptiveSpeedPipeline.h>
#include <risknav/speed/CScanMatchLocalizer.h>
#include <risknav/speed/TExploreOptions.h>

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace risknav::speed {
/** The stopping rule along the path the robot follows (Choi et al. (002)
 * eqs. 1-4, as CStoppingDistanceLimiter, but on the planned path instead of
 * a straight corridor, which a turning path leaves): a sensed point (ego
 * frame) closer than radius + lateralMargin to a path point within
 * radius + d_stop(v) + margin along the path, ahead of the robot, that
 * the path comes nearer to than the robot now is by more than
 * `noiseTolerance` [m] (a door post the robot stands beside is at the same
 * distance from the path within the sensor's noise: no reason to stop, and
 * stopping there would hold the robot in the doorway for ever). */
bool pathBlocked(const TPlannedPath& path,
                 const std::vector<mrpt::math::TPoint2D>& sensed, double v,
                 const common::TRobotOptions& robot, double margin, double lateralMargin,
                 double noiseTolerance = 0.01);

/** How an arrival the robot believed in went, in truth. */
struct TArrival {
    /** The robot truly stands within the allowed distance of the destination. */
    bool reached = false;
    /** What happened where the robot believed it had arrived (it halts there
     * and goes on: it cannot know better):
     *  - "reached": truly within the allowed distance;
     *  - "localization_error": not, and the belief's error (beliefError:
     *    odometry, the robot's own map) is at least the miss (trueError -
     *    allowed): the belief put the robot out of tolerance (always so
     *    when the belief was within it), or put the destination by a wall
     *    where the robot halted at the nearest point it believed it may
     *    come to;
     *  - "fell_short": not, with a smaller belief error: the robot halted
     *    where its own map (not its pose) said it could come no nearer. */
    const char* status = "localization_error";
    double trueError = 0;         ///< [m] true position to the destination
    double beliefError = 0;       ///< [m] believed position to the true position
    double believedDistance = 0;  ///< [m] believed position to the destination
    double allowed = 0;           ///< [m] the true distance that counts as reached
};

/** Judges, on the TRUE pose (the simulator's ground truth), an arrival at
 * `destination` (world frame) that the robot believed in at `believedPose`
 * (its belief placed in the world frame). Reached iff
 *
 *   |destination - true| < allowed = max(tolerance, nearestPossible + tolerance / 2)
 *
 * where nearestPossible [m] is how near the robot's centre may truly come to
 * a destination closer to an obstacle than the robot's radius and slowest
 * margin (0 in the open; the robot's own rule halts within tolerance / 2 of
 * the point nearest it). A miss is a "localization_error" when
 * beliefError >= |destination - true| - allowed (always so when the belief
 * was within allowed, as |destination - true| <= believedDistance +
 * beliefError), else "fell_short". A pure function. */
TArrival judgeArrival(const mrpt::math::TPoint2D& destination,
                      const mrpt::math::TPose2D& truePose,
                      const mrpt::math::TPose2D& believedPose, double tolerance,
                      double nearestPossible = 0);

/** One control cycle of a mode, as cycles.csv shows it. */
struct TCycleRecord {
    int cycle = 0;
    double t = 0;
    mrpt::math::TPose2D truePose, egoPose;
    double distance = 0;   ///< [m] travelled so far (true)
    double chosen = 0;     ///< [m/s] the controller's speed
    double commanded = 0;  ///< [m/s] after the stopping rule
    std::string reason;    ///< none | narrow | undecided | unreachable | obstacle
    double dUndecided = 0;
    std::vector<double> costToGo;  ///< per candidate speed (+inf: no path)
    int destination = 0;
    bool temporaryTarget = false, marginBroken = false;
    double computeMs = 0;  ///< localization + mapping + fusion + planning + selection
    double localizationMs = 0;  ///< of it, the scan matching (ego_motion = scan_matching)
};

/** A snapshot of the adaptive mode where its speed changes ((000) Fig. 16). */
struct TSnapshot {
    int cycle = 0;
    TPlanningField field;  ///< the fused map and its clearances, as planned on
    TSpeedDecision decision;
    mrpt::math::TPose2D egoPose;
};

/** One mode's run. */
struct TModeResult {
    std::string name;  ///< "adaptive" or "fixed_<v>"
    int fixedIndex = -1;
    std::vector<TCycleRecord> cycles;
    std::vector<mrpt::math::TPose2D> observations;  ///< true pose per cycle
    std::vector<TSnapshot> snapshots;
    /** reached | localization_error | fell_short | unreachable |
     * not_reached (the first three: judgeArrival() on the true pose, where
     * the robot believed it had arrived). */
    std::vector<std::string> destinationStatus;
    /** [m] true distance to the destination where the robot believed it had
     * arrived (judgeArrival()); NaN where it never did. */
    std::vector<double> destinationError;
    /** [m] the belief's position error there (believed vs true position, the
     * belief placed in the world by the start); NaN where it never arrived. */
    std::vector<double> destinationBeliefError;
    double time = 0, distance = 0;
    int collisions = 0, collisionsStatic = 0, nearMisses = 0, marginBrokenCycles = 0;
    double minClearance = 0;          ///< [m] robot edge to the map
    std::vector<double> timeAtSpeed;  ///< [s] per candidate speed (commanded)
    double timeStopped = 0;
    /** The scan matcher's counts at the end (ego_motion = scan_matching). */
    std::optional<CScanMatchLocalizer::TStats> localization;
    size_t localizationMapPoints = 0;
    bool allReached() const;
};

/** [m] The side of a memory centred on `start` that holds every destination
 * (x y pairs) with a local map of side `localMapSize` around it on every
 * side: max(configured, 2 (farthest destination + localMapSize)), at most
 * (maxCells - 1) x resolution; 0 stays 0 (no memory). Beyond the paper: a
 * memory that ends between the robot and its destination ranks the ways on
 * beyond its edge by the straight line from its border cells
 * (CFreeSpaceMemory::computeCostToGoal), and where the local map reaches
 * that edge those cells are the local map's free ones (left to the local
 * planner) or grown by the radius from the walls beside them: the way on
 * across the edge costs +inf. On maps larger than the 50 m memory the robot
 * swung between that way and a side room, or along a wall, until the
 * not-approaching alarm gave a reachable destination up. */
double exploreMemorySize(double configured, double resolution, double localMapSize,
                         const mrpt::math::TPoint2D& start,
                         const std::vector<double>& destinations, int maxCells = 4096);

/** risknav-explore on the closed loop (sim::CClosedLoop; Miura et al. 2006,
 * section 5, Fig. 13): a robot
 * that does not know the world visits destinations; each cycle of T it
 * senses (laser + RANGE2), moves its two local grids by the ego-motion,
 * updates, classifies and fuses them, and lets the adaptive controller (or a
 * fixed speed) choose a speed and path (those steps: CAdaptiveSpeedPipeline); a
 * pure-pursuit follower steers along the path for the cycle, and the stopping rule
 * (sensed obstacles within the stopping distance) may brake. The world (map, people,
 * clutter) is only used to simulate the sensors and to judge collisions.
 * The ego-motion (TExploreOptions::ego_motion) is by default the robot's own
 * localization, beyond the paper (which takes the ego-motion as given):
 * CScanMatchLocalizer aligns each laser scan to the point map built from the
 * earlier ones, odometry as the prior, and the grids are built on that
 * belief; odometry alone drifts with the wheels' systematic errors. */
class CExplorer {
  public:
    sim::CSimWorld world;
    TExploreOptions explore;
    TSpeedControlOptions speed;
    mapping::TSensorModel laserModel, range2Model;
    sim::CStoppingDistanceLimiter stopRule;
    /** The robot's localization when explore.ego_motion = scan_matching
     * (beyond the paper: CScanMatchLocalizer). */
    TScanMatchOptions scanMatch;

    /** Loads [Explore], [SpeedControl], [MapLaser], [MapRange2],
     * [CStoppingDistanceLimiter], [ScanMatching] and the world's sections; refuses
     * unknown sections and keys, destinations outside the map or inside an obstacle. */
    void loadFromConfigFile(const common::CIniConfig& c, std::optional<uint64_t> seed);
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;

    /** N of the configured models (the largest of the two sensors: the fused
     * map needs the slower one to confirm free space; see necessaryObservations). */
    int necessaryObservations() const;

    /** Runs one mode (fixedIndex -1: adaptive) from the start, same seed. */
    TModeResult runMode(int fixedIndex,
                        const std::function<void(double)>& progress = nullptr);

    /** The per-cycle pipeline's parameters from these options (the same
     * pipeline nav::CAdaptiveSpeedLimiter runs inside MRPT's engine); the
     * memory's side is memorySize(). */
    CAdaptiveSpeedPipeline::TParams pipelineParams() const;

    /** [m] The side of the memory the runs use (beyond the paper): [Explore]
     * memory_size, grown to exploreMemorySize() of the start and the
     * destinations; 0 when memory_size is 0 (no memory). */
    double memorySize() const;

  private:
    struct TModeRun;  // one mode's run on the closed loop (runMode())
    /** The pose the robot moves its maps by and steers with (the ego frame):
     * ground truth, odometry, or the scan matcher's belief moved on by the
     * odometry since its last scan. */
    mrpt::math::TPose2D egoPose() const;
    std::optional<CScanMatchLocalizer> m_localizer;
};
}  // namespace risknav::speed
