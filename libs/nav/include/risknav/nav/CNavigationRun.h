#pragma once
#include <risknav/common/CIniConfig.h>
#include <risknav/localization/CRawlogMcl.h>
#include <risknav/nav/TNavigateOptions.h>
#include <risknav/nav/waypoint_file.h>
#include <risknav/planning/CGlobalPlanner.h>
#include <risknav/risk/CRiskRouteChooser.h>
#include <risknav/sim/CAgentsSim.h>
#include <risknav/sim/CClosedLoop.h>
#include <risknav/sim/CSafetyMonitor.h>
#include <risknav/sim/CSimRobotInterface.h>
#include <risknav/sim/CSimWorld.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/CPolygon.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/nav/reactive/TWaypoint.h>
#include <mrpt/poses/CPose2D.h>

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace risknav::nav {
class CRiskAwareReactiveNav;

/** One navigation cycle, as cycles.csv shows it. */
struct TNavCycle {
    int cycle = 0;
    double t = 0;                                ///< [s] world time at the cycle's start
    mrpt::math::TPose2D truePose, believedPose;  ///< what the navigator was given
    double poseError = 0;                        ///< [m] |believed - true| position
    double speed = 0;      ///< [m/s] the robot's actual forward speed
    double command = 0;    ///< [m/s] the forward speed sent this cycle
    double desired = 0;    ///< [m/s] what MRPT's engine chose
    double limit = 0;      ///< [m/s] the smallest limit (= desired if none)
    std::string limiter;   ///< winning limiter, "" if none limited,
                           ///< "turn_in_place" when turning toward a target behind
    std::string reason;    ///< its reason
    double clearance = 0;  ///< [m] robot edge to the nearest map obstacle
    int waypoint = -1;     ///< the waypoint being approached
    double distance = 0;   ///< [m] travelled so far
    double stepMs = 0;     ///< wall time of navigationStep()
};

/** A timed event of a run (navigator events, tagged waypoints, fixes). */
struct TNavRunEvent {
    double t = 0;
    std::string kind;
    int waypoint = -1;
    double x = 0, y = 0;
    std::string detail;
};

/** Everything one closed-loop run produced. */
struct TNavRunResult {
    /** goal_reached | navigation_error | no_path | localization_error |
     * stalled | timeout */
    std::string status;
    std::string navError;  ///< MRPT's error code and message ("" if none)
    std::vector<TNavCycle> cycles;
    std::vector<TNavRunEvent> events;
    std::vector<mrpt::math::TPoint2D> track;  ///< true path, every physics step
    std::map<int, std::vector<mrpt::math::TPoint2D>> people;  ///< tracks by disc id
    std::vector<sim::TAgentEvent> agentEvents;
    sim::CSafetyMonitor safety;
    double time = 0, distance = 0;
    int waypointsReached = 0, waypointsSkipped = 0, waypointCount = 0;
    std::map<std::string, double> timePerLimiter;  ///< [s] "none" = no limit
    double finalPoseError = 0, maxPoseError = 0;   ///< [m]
    double navStepSeconds = 0;                     ///< wall time inside navigationStep()
    double wallSeconds = 0;
    size_t rawlogFrames = 0;
    int mrptErrors = 0;          ///< errors MRPT's navigator logged
    std::string firstMrptError;  ///< the first one's message
    std::string navlogFile;      ///< MRPT's file (in the run's log folder), "" if none
    /** The global planner's plans (global_planner = grid): every (re)plan. */
    std::vector<planning::TReplanEvent> plans;
    /** Every plan followed (a new one at each plan or replan that found a
     * way), in order. */
    std::vector<std::vector<mrpt::math::TPoint2D>> planPaths;
    double firstPlanLength = 0;  ///< [m]
    std::string noPathFailure;   ///< no way to a target: start_blocked | ...
    int localizationLost = 0;    ///< MCL found lost (and re-spread), localization = mcl
    std::vector<planning::TRouteChoice>
        routeChoices;  ///< global_planner = risk: per target
    /** [m] the least true distance of the robot to the last waypoint while
     * it was the target (+inf: never its target). "goal_reached" is MRPT's
     * verdict on the believed pose; farther than goal_tolerance (+ 3 cm:
     * the track is sampled every sim_dt, 5.5 cm apart at 1.1 m/s) it
     * becomes status "localization_error". */
    double goalTrueDistance = std::numeric_limits<double>::infinity();
    int collisions() const { return safety.collisions() + safety.collisionsStatic(); }
};

/** What may differ between the runs of one config (experiments). */
struct TNavRunSetup {
    uint64_t seed = 1;
    std::optional<double> maxSpeed;  ///< [m/s] the engine's robotMax_V_mps
    /** Limiter class names instead of [CRiskAwareReactiveNav] speed_limiters. */
    std::optional<std::vector<std::string>> limiters;
    std::optional<std::string> afraidFile;  ///< [CAfraidSpeedLimiter] afraid_file
    std::optional<int> laps;
    std::string navlogDir;        ///< "" = no navlog
    std::string rawlogPath;       ///< "" = no rawlog
    std::string groundtruthPath;  ///< "t x y phi" per rawlog frame ("" = none)
    bool quiet = true;
    std::string label;  ///< progress label
};

/** risknav-navigate on the closed loop (sim::CClosedLoop): MRPT's reactive engine with
 * risknav's limiters (CRiskAwareReactiveNav) drives the steppable world
 * (CSimWorld, people included) through MRPT's robot interface on MRPT's
 * simulated clock. Each cycle of nav_period: the world is sensed, the
 * localizer (ground truth, the drifting odometry with fixes at sensing
 * points, or MCL on the laser) gives the pose the navigator sees, the
 * frame goes to the rawlog, navigationStep() runs, and the world advances in
 * sim_dt steps while the loop's CSafetyMonitor counts collisions and near misses.
 *
 * Config: [Navigate] (TNavigateOptions), the world's sections (CSimWorld),
 * MRPT's engine sections ([CAbstractNavigator], [CWaypointsNavigator],
 * [CAbstractPTGBasedReactive], [CReactiveNavigationSystem], the holonomic
 * method's, ...), [CRiskAwareReactiveNav] and each limiter's section, and
 * for localization = mcl [Localization] [PF_options] [KLD_options]. */
class CNavigationRun {
  public:
    TNavigateOptions options;  ///< [Navigate]
    sim::CSimWorld world;
    localization::CRawlogMcl mcl;            ///< [Localization] etc. (localization = mcl)
    mrpt::nav::TWaypointSequence waypoints;  ///< one lap of the route
    std::map<size_t, TWaypointTag> tags;     ///< by waypoint index
    std::string routeName;                   ///< where the route came from
    /** [GlobalPlanner] (global_planner = grid). */
    planning::CGlobalPlanner::TOptions plannerOptions;

    /** Loads and checks everything (the world, the route against the map,
     * MRPT's engine and the limiters through a probe navigator), before any
     * output. Keeps a reference to `c` for the runs. Sections the caller
     * loads itself are listed in `otherSections` (not reported unknown). */
    void loadFromConfigFile(common::CIniConfig& c, std::optional<uint64_t> seed,
                            const std::vector<std::string>& otherSections = {});
    /** Every key the run reads: [Navigate], the world's sections, MRPT's
     * engine sections as the engine loaded them (engine_config included),
     * [CRiskAwareReactiveNav], [Robot], each limiter's and sensor model's
     * section, and MCL's; loaded as a config, it reproduces the run. */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;

    /** The waypoints of a run of `laps` laps (mode back_and_forth / loop). */
    mrpt::nav::TWaypointSequence lapWaypoints(int laps) const;
    /** Runs one closed loop from the start. */
    TNavRunResult run(const TNavRunSetup& setup);
    /** The PTG cache folder used. */
    std::string ptgCacheDir() const;

  private:
    common::CIniConfig* m_cfg = nullptr;
    std::unique_ptr<common::CIniConfig> m_engine;  // [Navigate] engine_config
    // the probe navigator's saveConfigFile(): the engine and limiter sections
    mrpt::config::CConfigFileMemory m_navigatorConfig;
    std::shared_ptr<planning::CGlobalPlanner> m_planner;  // its map set up once
    std::unique_ptr<risk::CRiskRouteChooser> m_chooser;   // global_planner = risk
    risk::TPropagationOptions m_propagation;              // [Odometry], for the chooser
    void loadRoute(common::CIniConfig& c);
    // loadFromConfigFile()'s parts (CNavigationRun_config.cpp)
    void setUpGlobalPlanner(const common::CIniConfig& c);
    void checkOutputBounds(const common::CIniConfig& c) const;
    void checkWithProbeNavigator(common::CIniConfig& c,
                                 const std::vector<std::string>& otherSections);
    void checkLaserHeight(const common::CIniConfig& c,
                          const CRiskAwareReactiveNav& probe) const;
    void checkLimiterInputs(const common::CIniConfig& c,
                            const CRiskAwareReactiveNav& probe) const;
    void checkSectionsKnown(common::CIniConfig& c, const CRiskAwareReactiveNav& probe,
                            const std::vector<std::string>& otherSections) const;
    void checkAgainstMap(const common::CIniConfig& c) const;
    /** MRPT's engine as configured (limiters aside) on MRPT's own simulated
     * robot in open space, a target 3 m ahead: the error it fails with on
     * each of its first cycles, "" when it moves. Tells a config MRPT takes
     * unchecked from a start its PTGs find no motion from. */
    // run()'s parts (CNavigationRun.cpp), on one run's state
    struct TRun;
    void applyRunSetup(const TNavRunSetup& setup);
    void startNavigator(TRun& s);
    void aimWaypoints(TRun& s) const;
    void openRunOutputs(TRun& s);
    bool runCycle(TRun& s, int cycle);
    mrpt::math::TPose2D senseAndLocalize(TRun& s, double t);
    const TNavCycle& stepNavigator(TRun& s, int cycle, double t,
                                   const mrpt::math::TPose2D& truth);
    void takeNavEvents(TRun& s, const mrpt::math::TPose2D& truth, double poseError);
    void checkEngineFailures(TRun& s, int cycle, double t,
                             const mrpt::math::TPose2D& truth) const;
    bool runEnds(TRun& s, int cycle, double t, const mrpt::math::TPose2D& truth) const;
    void startSteps(TRun& s);
    void endSteps(TRun& s);
    void finishRun(TRun& s);
    const TWaypointTag* tagOf(int waypoint) const;
    mrpt::poses::CPose2D odoFixFor(const mrpt::math::TPose2D& pose) const;
    std::string engineFailsInOpenSpace(const std::string& cacheDir,
                                       double clockNow) const;
    /** The robot shape MRPT gets: [Robot] radius grown by shape_margin. */
    mrpt::math::CPolygon robotShape() const;
};

}  // namespace risknav::nav
