#pragma once
#include <risknav/common/CSpeedLimiter.h>
#include <risknav/common/CValidatedOptions.h>
#include <risknav/common/CWorkerThread.h>
#include <risknav/mapping/TSensorModel.h>
#include <risknav/speed/CAdaptiveSpeedPipeline.h>
#include <risknav/speed/TSpeedControlOptions.h>

#include <mrpt/obs/CObservation2DRangeScan.h>

#include <deque>
#include <memory>
#include <optional>
#include <string>

namespace risknav::nav {
/** The adaptive speed control of Miura, Negishi, Shirai 2006 (000) (M1) as a
 * speed limiter inside MRPT's reactive engine (CRiskAwareReactiveNav).
 *
 * Each cycle (one navigator sensing) it runs speed::CAdaptiveSpeedPipeline, the
 * same per-cycle pipeline as risknav-explore: the robot's own two
 * robot-centred uncertain grids (laser `scan`, second range sensor `scan2`)
 * follow the believed pose (ego-motion, (000) section 2) and take the scans
 * (Bayes update of section 2), are classified and fused (section 2), and the
 * adaptive controller plans to the navigator's target (`in.target`; a
 * temporary destination on the free / undecided boundary when it is not in
 * known free space, section 3.3) for each candidate speed with its margin
 * and returns the fastest safe speed (section 5, Fig. 13):
 *  - the narrow-space gap rule on the per-speed cost-to-go (section 4.1),
 *    faster speeds still allowed while their margin holds for the next
 *    lookahead_cycles cycles (section 4.2): reason "narrow passage ...";
 *  - the undecided-region rule d / (v T) >= N (section 3.1, d along the
 *    path, N of section 3.2 from the sensor models): reason "undecided
 *    region x.xx m ahead";
 *  - no path and no frontier: 0, reason "unreachable".
 * The limit is that speed; when it is not below the desired speed the
 * limiter does not limit (desired speed, empty reason). MRPT's engine keeps
 * choosing the motion; the limiter only bounds its speed.
 *
 * The cycle time T (measure_cycle_time = true, the default): the navigator's
 * own cycle, measured: per sensor, the median of the last 16 intervals [s]
 * (TSpeedLimitInput::time) between cycles that brought a scan of it; the
 * rule's N T is max over the fused sensors of N_s T_s (a decimated RANGE2 is
 * observed less often than the laser), given to the controller as
 * T = max_s(N_s T_s) / N with N = max_s N_s. Until an interval has been
 * measured, and with measure_cycle_time = false, T = cycle_time.
 *
 * Beyond the paper (as risknav-explore's creep): a robot held at 0
 * (undecided or unreachable) for N cycles in a row has observed what it can
 * see from there N times; the limit then becomes the slowest candidate
 * speed (reason "... held N cycles: creeping"), so that MRPT's engine, which
 * steers and avoids obstacles itself, can move (or turn) on and look.
 * The robot's radius comes from TSpeedLimitInput::robot ([Robot]).
 *
 * The cycle's schedule (beyond the paper, which plans once per sensing
 * cycle of ~0.3 s; MRPT's engine senses every 0.2 s here): the map-and-plan
 * cycle runs on every cycle_decimation-th sensing (default 1: every one),
 * on the latest scan of each sensor since the cycle before, each taken at
 * the pose of its own sensing (a decimated RANGE2 is kept until a cycle
 * takes it). T, measured as above between the scans a cycle took, is then
 * the cycle's period, and the undecided rule d / (v T) >= N accounts for
 * it. The navigator calls observe() right after it sensed; on a cycle's
 * sensing the cycle starts there, on a worker thread (worker_thread = true;
 * it needs nothing MRPT's engine decides) or on the caller's thread.
 *  - cycle_decimation = 1: limit() in the same navigator cycle waits for
 *    that cycle and takes its decision (no latency).
 *  - cycle_decimation = n >= 2: a cycle's decision is taken when the next
 *    cycle starts, n sensings later, and holds for the n sensings after
 *    that; the cycle runs on the worker beside the engine for those n
 *    navigator cycles. The decision acts n to 2n - 1 sensings after its
 *    scans: 0.4-0.6 s for n = 2, the age a decision has on the paper's
 *    robot, whose one cycle (~0.3 s) senses, plans and then holds its
 *    command for the next (a cycle's latency equals its period T, which
 *    the rule's T covers). The first cycle of a run is waited for (no
 *    limit is given without a decision), and so is the cycle of a sensing
 *    whose target differs from the sensing before (a waypoint reached):
 *    that sensing starts a cycle whatever the count (the next one is n
 *    sensings later), so that no speed or guide point planned to the old
 *    waypoint acts on the way to the new one (with n = 2 and decisions to
 *    the old one for two more sensings, 3 of 5 M1 hall runs stalled; with
 *    this rule all 5 reached their goal, though two slowly: see
 *    cycle_decimation below).
 * On the worker, a caller that waits for the cycle (limit(), the end of
 * the navigator's cycle) meanwhile runs some of its independent parts
 * itself (the two sensors' grids, the planning field's two distance fields
 * beside the memory's update, the per-speed plans, the plans to the goal
 * beside the choice of the target: common::CWorkerThread::parallelFor()),
 * so the navigator's thread, idle
 * once MRPT has evaluated its motions, shortens the cycle.
 * The same decisions on the worker and the caller's thread, and for a
 * caller that only calls limit() (each call is then a sensing). A cycle
 * runs on every cycle's sensing, also one in which the engine then
 * commands no forward speed (and so calls no limiter).
 *
 * Section [CAdaptiveSpeedLimiter] (every key optional; unknown keys are
 * refused):
 *   speeds               [m/s]  1.1 0.7 0.35 0.2  candidates, fastest first
 *   margins              [m]    0.30 0.20 0.10 0.05  per speed (section 6)
 *   gap_threshold        [m]    1.0   cost-to-go jump = narrow passage (4.1)
 *   lookahead_cycles     [-]    2     section 4.2
 *   occupied_threshold   [-]    0.7   classification (section 2)
 *   free_threshold       [-]    0.2   classification; also defines N
 *   frontier_goal_weight [-]    2.0   temporary destination cost (beyond)
 *   target_switch_cost   [m]    3.0   temporary destination hysteresis
 *   cycle_time           [s]    0.3   T when not measured (see above)
 *   measure_cycle_time   [bool] true  T from the time between cycles
 *   fixed_speed_index    [-]    -1    -1 adaptive; k: fixed at speeds[k]
 *                                     (the paper's baseline, section 6)
 *   laser_model          [name] ""    section with the laser's sensor model
 *                                     (p_obs_given_obstacle, p_obs_given_free,
 *                                     range_uncertainty[_quad], as [MapLaser]
 *                                     of risknav-explore); "" = 0.7 / 0.3 /
 *                                     0.05 m (N = 2)
 *   range2_model         [name] ""    the same for `scan2` ([MapRange2]);
 *                                     "" = 0.6 / 0.45 / 0.05 m (N = 5)
 *   use_range2           [bool] true  fuse the second sensor; false: the
 *                                     laser alone (N = the laser's)
 *   local_map_size       [m]    10    side of the robot-centred grids
 *   local_map_resolution [m]    0.05
 *   memory_size          [m]    50    coarse free-space memory; 0 = none
 *   memory_resolution    [m]    0.25
 *   worker_thread        [bool] true  run the observed cycle on a worker
 *                                     thread beside the engine; false: on
 *                                     the navigator's (the same decisions)
 *   cycle_decimation     [-]    1     the cycle runs on every n-th sensing
 *                                     (1..100; see above: 2 halves the
 *                                     cycle's CPU a step, but maps half the
 *                                     scans: M1 stalled or crawled in 3 of
 *                                     5 hall runs)
 * A named model section that does not exist is an error. */
class CAdaptiveSpeedLimiter : public common::CSpeedLimiter {
    DEFINE_MRPT_OBJECT(CAdaptiveSpeedLimiter, risknav::nav)
  public:
    struct TOptions : public common::CDeclaredOptions {
        /** speeds, margins, gap_threshold, lookahead_cycles, thresholds,
         * frontier_goal_weight, target_switch_cost, cycle_time: the keys of
         * risknav-explore's [SpeedControl], read from this section. */
        speed::TSpeedControlOptions speed;
        bool measure_cycle_time = true;
        /** -1: adaptive; k >= 0: fixed at candidate k (the paper's fixed-speed
         * baseline, section 6: its own margin, no undecided rule). */
        int fixed_speed_index = -1;
        std::string laser_model, range2_model;  ///< section names, "" = defaults
        mapping::TSensorModel laser, range2;    ///< as read from them
        bool use_range2 = true;
        double local_map_size = 10.0;        ///< [m]
        double local_map_resolution = 0.05;  ///< [m]
        double memory_size = 50.0;           ///< [m], 0 = none
        double memory_resolution = 0.25;     ///< [m]
        bool worker_thread = true;           ///< observed cycles beside the engine
        int cycle_decimation = 1;            ///< a cycle every n-th sensing

        TOptions();

      protected:
        /** Also the named model sections (CBadInputError when one is
         * missing; range2's checked only with use_range2). */
        void declare(Visitor& v) override;
        /** The grids' sizes, and that N exists for each fused model. */
        void validateRules() const override;
    } options;

    /** Loads and validates options (CBadInputError naming file, section,
     * key); refuses unknown keys in the section. Resets the map. */
    void loadConfig(const mrpt::config::CConfigFileBase& c,
                    const std::string& section) override;
    void saveConfig(mrpt::config::CConfigFileBase& c,
                    const std::string& section) const override;

    /** Forgets the map and the measured cycle (a new run). */
    void reset();
    /** The look-ahead point (speed::lookaheadPoint) on the last decision's
     * path, from `pose`; nullopt before the first decision, when it found
     * no way (unreachable), its path has fewer than 2 points, or the straight
     * line to the goal is open on its map (known free cells with the robot's
     * radius to spare, as far as the map reaches). */
    std::optional<mrpt::math::TPoint2D> guidePoint(const mrpt::math::TPose2D& pose,
                                                   double lookahead) const override;
    /** The decision limit() uses now (the last one taken; nullopt before
     * the first planned cycle). */
    const std::optional<speed::TSpeedDecision>& lastDecision() const {
        return m_adopted.decision;
    }
    /** The T [s] that decision used. */
    double lastCycleTime() const { return m_adopted.T; }
    /** N of the configured models. */
    int necessaryObservations() const;
    /** The pipeline (grids, fused map) after the last cycle that started
     * (waits for it; with cycle_decimation >= 2 it may be a cycle ahead of
     * lastDecision()); null before the first. Its planning field is not
     * there: each cycle moves it out, beside its decision. */
    const speed::CAdaptiveSpeedPipeline* pipeline() const {
        waitCycle();
        return m_pipeline.get();
    }
    /** With cycle_decimation = 1, and for a new target's cycle, waits for
     * the cycle observe() started (and takes its decision): none outlives
     * the navigator's cycle. Otherwise (n >= 2) a cycle runs on across the
     * navigator's cycles until the next one starts (which waits for it and
     * rethrows its error). */
    void finishObserved() const override;

  protected:
    common::TSpeedLimit impl_limit(const common::TSpeedLimitInput& in) const override;
    void impl_observe(const common::TSpeedLimitInput& in) const override;

  private:
    /** A scan kept for a cycle, with the pose and time of its sensing. */
    struct TKeptScan {
        mrpt::obs::CObservation2DRangeScan scan;
        mrpt::math::TPose2D pose;
        // no member initializer: clang then deems the struct not
        // default-constructible inside the class (std::optional::emplace());
        // emplace() value-initializes it to 0 all the same
        double time;
    };
    /** What one cycle reads (the caller's thread fills it before the cycle
     * starts; the cycle owns it while it runs). */
    struct TCycleInput {
        mrpt::math::TPose2D pose;
        std::optional<mrpt::math::TPoint2D> target;
        double radius = 0;
        std::optional<TKeptScan> laser, range2;
    };
    /** What one cycle decided, and the field it planned on (guidePoint). */
    struct TCycleResult {
        bool valid = false;
        std::optional<speed::TSpeedDecision> decision;
        std::optional<mrpt::math::TPoint2D> goal;  ///< its input target
        bool creep = false;                        ///< the decision held long enough at 0
        double T = 0;
        speed::TPlanningField field;
    };

    /** A sensing: a new run is detected, the scans kept and, on a cycle's
     * sensing, the previous cycle's decision taken (n >= 2) and the cycle
     * started. */
    void sense(const common::TSpeedLimitInput& in) const;
    /** One cycle on m_cycleIn: the measured T, the map update and, with a
     * target, the decision; into m_result. */
    void runCycle() const;
    void waitCycle() const;  ///< the cycle in flight ends (rethrows its error)
    void adopt() const;      ///< m_result becomes the decision limit() uses
    void takeCycle() const;  ///< the cycle in flight, if any, ends and is adopted
    speed::CAdaptiveSpeedPipeline::TParams params(double radius, double T) const;
    double cycleTime() const;
    void resetState() const;  ///< the mutable state only

    // The limiter's state (limit() is const, the plugin interface; the map
    // it builds is not). The cycle's own (touched only by runCycle(), on the
    // worker while a cycle is in flight):
    mutable std::unique_ptr<speed::CAdaptiveSpeedPipeline> m_pipeline;
    mutable std::optional<double> m_lastLaser, m_lastRange2;  ///< scan times
    mutable std::deque<double> m_dtLaser, m_dtRange2;
    mutable std::optional<mrpt::math::TPoint2D> m_previousTarget;
    mutable TCycleInput m_cycleIn;
    mutable TCycleResult m_result;
    // the caller's:
    mutable TCycleResult m_adopted;   ///< the decision limit() uses
    mutable bool m_inFlight = false;  ///< a cycle started, its result not taken
    mutable size_t m_sensings = 0;    ///< since the run began
    mutable std::optional<double> m_lastSensing;
    mutable std::optional<mrpt::math::TPoint2D> m_lastTarget;  ///< of that sensing
    mutable bool m_retargeted = false;  ///< the cycle in flight is a new target's
    mutable double m_radius = 0;
    mutable std::optional<TKeptScan> m_keptLaser, m_keptRange2;  ///< since the last cycle
    /** Time of the sensing observe() saw that no limit() has used yet. */
    mutable std::optional<double> m_observed;
    /** Last member: destroyed first, so its job ends while the state lives. */
    mutable std::unique_ptr<common::CWorkerThread> m_worker;
};

}  // namespace risknav::nav
