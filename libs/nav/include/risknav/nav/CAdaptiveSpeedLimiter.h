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
 * One cycle per sensing: the navigator calls observe() right after it
 * sensed, and the cycle (map update, plans, decision) runs there, on a
 * worker thread while MRPT's engine evaluates its motions (worker_thread =
 * true; it needs nothing the engine decides); limit() in the same cycle
 * waits for it and compares its speed with the desired one. A cycle is run
 * on every sensing, also one in which the engine then commands no forward
 * speed (and so calls no limiter). A caller that does not observe() gets
 * the cycle run inside limit(), as before.
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
 * A named model section that does not exist is an error. */
class CAdaptiveSpeedLimiter : public common::CSpeedLimiter {
    DEFINE_MRPT_OBJECT(CAdaptiveSpeedLimiter, risknav::nav)
  public:
    struct TOptions : public common::CValidatedOptions {
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
        std::string section = "CAdaptiveSpeedLimiter";

        TOptions();
        /** Also reads the named model sections (CBadInputError when one is
         * missing). */
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                              const std::string& s) const override;
        /** Ranges of every key, the [SpeedControl] rules, the sensor models,
         * and that N exists for each fused model. */
        void validate() const override;
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
    /** The last cycle's decision (nullopt before the first planned cycle). */
    const std::optional<speed::TSpeedDecision>& lastDecision() const {
        finishObserved();
        return m_last;
    }
    /** The T [s] the last decision used. */
    double lastCycleTime() const {
        finishObserved();
        return m_lastT;
    }
    /** N of the configured models. */
    int necessaryObservations() const;
    /** The pipeline (map, field) of the last call; null before the first. */
    const speed::CAdaptiveSpeedPipeline* pipeline() const {
        finishObserved();
        return m_pipeline.get();
    }
    void finishObserved() const override;

  protected:
    common::TSpeedLimit impl_limit(const common::TSpeedLimitInput& in) const override;
    void impl_observe(const common::TSpeedLimitInput& in) const override;

  private:
    /** One cycle: the measured T, the map update and, with a target, the
     * decision (m_last, m_creep). */
    void runCycle(const common::TSpeedLimitInput& in) const;
    speed::CAdaptiveSpeedPipeline::TParams params(double radius, double T) const;
    double cycleTime() const;
    void resetState() const;  ///< the mutable state only

    // the limiter's state: limit() is const (the plugin interface), the map
    // it builds is not
    mutable std::unique_ptr<speed::CAdaptiveSpeedPipeline> m_pipeline;
    mutable double m_radius = 0, m_lastT = 0;
    mutable std::optional<double> m_lastTime, m_lastLaser, m_lastRange2;
    mutable std::deque<double> m_dtLaser, m_dtRange2;
    mutable std::optional<mrpt::math::TPoint2D> m_previousTarget;
    mutable std::optional<speed::TSpeedDecision> m_last;
    mutable std::optional<mrpt::math::TPoint2D> m_lastGoal;  ///< its input target
    mutable bool m_creep = false;  ///< the last decision held long enough at 0
    /** The scans of the cycle on the worker (copies). */
    mutable std::optional<mrpt::obs::CObservation2DRangeScan> m_scanCopy, m_scan2Copy;
    /** Time of the cycle observe() ran that no limit() has used yet. */
    mutable std::optional<double> m_observed;
    /** Last member: destroyed first, so its job ends while the state lives. */
    mutable std::unique_ptr<common::CWorkerThread> m_worker;
};

}  // namespace risknav::nav
