#pragma once
#include <risknav/sim/CSafetyMonitor.h>
#include <risknav/sim/CSimWorld.h>

#include <mrpt/math/TPose2D.h>

#include <limits>

namespace risknav::sim {
/** The closed loop of every app that steps the world (risknav-simulate,
 * risknav-explore, risknav-navigate): cycle after cycle, the controller
 * senses, decides and records (onCycle()), then the world advances
 * steps_per_cycle sub-steps of sim_dt, each one commanded (onSubStep()),
 * stepped, measured (the distance driven) and watched by a CSafetyMonitor
 * (collisions, near misses and, if asked, people entering the stopping
 * corridor) before onStepped() sees it.
 *
 * The loop ends when onCycle() returns false (the controller's own ending:
 * the route done, the navigator idle, ...) or, after a cycle was recorded,
 * at duration_max. Derive from it and override the hooks, as one derives
 * from mrpt::nav::CAbstractNavigator:
 *
 * \code
 * struct TMyRun : public CClosedLoop {
 *     using CClosedLoop::CClosedLoop;
 *     bool onCycle(int cycle) override { ...sense, decide, record...; return true; }
 *     void onSubStep(int, int) override { world.command(v, w); }
 * };
 * TMyRun run(world, opts);
 * const auto end = run.run();
 * \endcode */
class CClosedLoop {
  public:
    struct TOptions {
        double sim_dt = 0.05;     ///< [s] one physics sub-step
        int steps_per_cycle = 1;  ///< sub-steps per control cycle
        /** [s] world time at which a recorded cycle ends the loop (Timeout);
         * +inf: only the controller ends it. */
        double duration_max = std::numeric_limits<double>::infinity();
        /** Watch door pedestrians entering the stopping corridor
         * (CSafetyMonitor::updateCorridor()): the stopping distance plus
         * corridor_beta [m] ahead, the radius plus corridor_lateral_margin
         * [m] to each side. */
        bool watch_corridor = false;
        double corridor_beta = 0, corridor_lateral_margin = 0;
        /** How a sub-step's end is timed for the monitor: false, the world's
         * time after it; true, its time before it plus sim_dt (as
         * risknav-simulate's events have always been timed; the two may
         * differ in the last bit). */
        bool time_as_sum = false;
    };
    /** Why run() returned. */
    enum class TEnd { Controller, Timeout };

    CClosedLoop(CSimWorld& world, const TOptions& options);
    virtual ~CClosedLoop() = default;

    /** Runs cycles from cycle 0 until the loop ends. */
    TEnd run();

    CSimWorld& world;
    const TOptions options;
    /** Every sub-step's collisions and near misses. Set near_miss_distance
     * before run(). */
    CSafetyMonitor safety;
    /** [m] the true distance driven, summed over the sub-steps. */
    double travelled() const { return m_travelled; }
    /** Cycles that were recorded (onCycle() calls). */
    int cycles() const { return m_cycles; }

  protected:
    /** Start of a cycle: sense, decide, command, record. false ends the loop
     * (the world does not move again). */
    virtual bool onCycle(int cycle) = 0;
    /** The cycle goes on (not ended): before its sub-steps. */
    virtual void onCycleSteps(int /*cycle*/) {}
    /** Before sub-step k of the cycle: the command for it, if any. */
    virtual void onSubStep(int /*cycle*/, int /*k*/) {}
    /** After sub-step k, once monitored: the true pose now. */
    virtual void onStepped(int /*cycle*/, int /*k*/, const mrpt::math::TPose2D& /*now*/) {
    }
    /** After the cycle's sub-steps. */
    virtual void onCycleEnd(int /*cycle*/) {}

  private:
    void monitor(double t, const mrpt::math::TPose2D& now);
    double m_travelled = 0;
    int m_cycles = 0;
};

}  // namespace risknav::sim
