#pragma once
#include <risknav/mapping/CFreeSpaceMemory.h>
#include <risknav/mapping/CLocalProbGrid.h>
#include <risknav/mapping/TSensorModel.h>
#include <risknav/mapping/free_space.h>
#include <risknav/speed/CAdaptiveSpeedController.h>
#include <risknav/speed/TPlanningField.h>
#include <risknav/speed/TSpeedControlOptions.h>

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <memory>
#include <optional>
#include <utility>

namespace risknav::speed {
/** Marks the undecided cells under a robot disc at p as free (obstacle
 * cells stay: a sensed obstacle there is a collision to see, not to hide). */
void markFootprintFree(mapping::TFreeSpaceMap& m, const mrpt::math::TPose2D& p,
                       double radius);

/** One control cycle of the adaptive speed control of Miura, Negishi, Shirai
 * 2006 (000), the part that does not depend on who drives the robot
 * (risknav-explore's CExplorer, or MRPT's reactive engine through
 * nav::CAdaptiveSpeedLimiter):
 *  update(): the two robot-centred per-sensor grids follow the ego-motion
 *    ((000) section 2; here by whole-cell scrolls, see CLocalProbGrid), take
 *    this cycle's scans (the forward sensor model and Bayes update of section
 *    2), are classified (P > occupied_threshold obstacle, P < free_threshold
 *    free, else undecided with / without observation) and fused (free iff
 *    both free, or one free and the other undecided-with-observation); the
 *    robot's own footprint is free (beyond the paper, markFootprintFree); the
 *    planning field (clearances, frontier) is computed and the coarse
 *    free-space memory (beyond the paper, CFreeSpaceMemory) updated;
 *  decide(): CAdaptiveSpeedController::decide() on that field (sections
 *    3-5, Fig. 13): the narrow-space gap rule (section 4.1, 4.2) and the
 *    undecided-region rule d / (v T) >= N (section 3.1), T =
 *    TParams::speed.cycle_time, N = necessaryObservations().
 * All in one frame, the ego frame (odometry, ground truth or a localization
 * estimate: whatever the caller's poses are in). */
class CAdaptiveSpeedPipeline {
  public:
    struct TParams {
        TSpeedControlOptions speed;  ///< candidates, thresholds, T = cycle_time
        mapping::TSensorModel laserModel, range2Model;
        /** Fuse the second sensor's grid; false: the laser's grid is fused
         * with itself (one sensor) and N is the laser model's. */
        bool useRange2 = true;
        double robotRadius = 0.25;         ///< [m]
        double localMapSize = 10.0;        ///< [m] side of the grids
        double localMapResolution = 0.05;  ///< [m]
        double memorySize = 50.0;          ///< [m] side of the memory; 0 = none
        double memoryResolution = 0.25;    ///< [m]
    };

    /** N of (000) section 3.2 for the configured models: the largest of the
     * fused sensors' (the fused map needs the slower one to confirm free
     * space). Throws std::invalid_argument for a model that never decides. */
    static int necessaryObservations(const TParams& p);

    /** Empty grids centred on ego0; throws std::invalid_argument for bad
     * parameters (the controller validates its options). */
    CAdaptiveSpeedPipeline(const TParams& p, const mrpt::math::TPose2D& ego0);

    /** Mapping, fusion and planning field of one cycle; a null scan is no
     * observation of that sensor this cycle. */
    void update(const mrpt::math::TPose2D& ego,
                const mrpt::obs::CObservation2DRangeScan* laser,
                const mrpt::obs::CObservation2DRangeScan* range2) {
        update(ego, laser, ego, range2, ego);
    }
    /** The same with each scan taken at its own pose (a scan of an earlier
     * sensing, e.g. a decimated sensor's, kept for this cycle); the grids
     * follow `ego`. */
    void update(const mrpt::math::TPose2D& ego,
                const mrpt::obs::CObservation2DRangeScan* laser,
                const mrpt::math::TPose2D& laserPose,
                const mrpt::obs::CObservation2DRangeScan* range2,
                const mrpt::math::TPose2D& range2Pose);

    /** The controller on the latest field (after update()); the memory's
     * cost to the goal ranks temporary destinations when there is a memory.
     * `previousTarget`: the temporary destination of the previous cycle
     * (hysteresis, TTargetHints). At most once per update(). */
    TSpeedDecision decide(const mrpt::math::TPose2D& ego,
                          const mrpt::math::TPoint2D& goal, int fixedIndex = -1,
                          const std::optional<mrpt::math::TPoint2D>& previousTarget = {});

    /** Changes T of the undecided rule (e.g. a measured cycle); the maps
     * stay. Throws std::invalid_argument unless 0 < T <= 10 s. */
    void setCycleTime(double T);

    /** How a cycle runs its independent parts (the two sensors' grids; the
     * planning field's two distance fields beside the memory's update; the
     * per-speed plans): empty (the default) one after the other, or e.g. a
     * worker's CWorkerThread::parallelFor(). The same results either way. */
    void setParallelFor(common::TParallelFor parallel);

    /** Beyond the paper: a robot held (speed 0) has, after N held cycles in
     * place, observed what it sees N times; what is still undecided then (a
     * gap in a wall seen edge-on) will not be decided from there, so the
     * caller may creep on at the slowest speed. Call once a cycle with
     * whether the robot is held; true once it has been held N cycles in a
     * row (and for every further held cycle). */
    bool heldLongEnough(bool held);

    const TParams& params() const { return m_p; }
    const CAdaptiveSpeedController& controller() const { return m_ctrl; }
    const mapping::CLocalProbGrid& laserGrid() const { return m_laser; }
    const mapping::CLocalProbGrid& range2Grid() const { return m_range2; }
    const mapping::TFreeSpaceMap& fused() const { return m_fused; }
    const TPlanningField& field() const { return m_field; }
    /** Moves this cycle's field out, for a caller that keeps it (no copy):
     * field() is empty, and decide() refuses, until the next update(). */
    TPlanningField takeField() {
        TPlanningField f = std::move(m_field);
        m_field = TPlanningField{};
        return f;
    }

  private:
    TParams m_p;
    CAdaptiveSpeedController m_ctrl;
    mapping::CLocalProbGrid m_laser, m_range2;
    std::unique_ptr<mapping::CFreeSpaceMemory> m_memory;
    mapping::TFreeSpaceMap m_fused;
    TPlanningField m_field;
    /** The next field's ways on computed with its clearance (the last
     * decision's target was not the goal), else at the first read. */
    bool m_wayOnAhead = true;
    int m_held = 0;
    common::TParallelFor m_parallel;
};
}  // namespace risknav::speed
