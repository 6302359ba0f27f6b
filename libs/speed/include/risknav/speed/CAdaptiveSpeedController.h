#pragma once
#include <risknav/common/parallel_for.h>
#include <risknav/speed/IPathPlanner.h>
#include <risknav/speed/TSpeedControlOptions.h>

#include <mrpt/math/TPose2D.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace risknav::speed {
/** Why a cycle's speed is what it is. */
enum class TSpeedReason {
    None,         ///< the fastest candidate
    Narrow,       ///< a narrow passage (gap rule, section 4)
    Undecided,    ///< the distance to an undecided region (section 3)
    Unreachable,  ///< no path and no frontier: the robot stops
};
const char* reasonName(TSpeedReason r);

/** Cost [m] of the way on from an ego-frame point to the goal, used to rank
 * temporary destinations; empty: frontier_goal_weight x the straight line. */
using TGoalCost = std::function<double(double x, double y)>;

/** What the caller knows beyond one map (beyond the paper): the cost of the
 * way on, and the temporary destination of the previous cycle (candidates
 * farther than 1 m from it pay target_switch_cost: a choice that flips with
 * every few centimetres of motion, as a wall enters and leaves the local
 * map's edge, would hold the robot in a doorway). */
struct TTargetHints {
    TGoalCost goalCost;
    std::optional<mrpt::math::TPoint2D> previous;
};

/** One cycle's decision, everything the outputs show. */
struct TSpeedDecision {
    double speed = 0;     ///< [m/s] 0 = stop
    int speedIndex = -1;  ///< into the candidate list, -1 = stop
    TSpeedReason reason = TSpeedReason::None;
    std::vector<TPlannedPath> perSpeed;  ///< the plan of each candidate speed
    int pathIndex = -1;                  ///< whose plan the robot follows
    TPlannedPath path;                   ///< that plan
    std::vector<size_t> safeByGap;       ///< section 4.1
    std::vector<size_t> allowed;         ///< after section 4.2 (faster on the path)
    double dUndecided = 0;               ///< [m] along the path, +inf = none
    mrpt::math::TPoint2D target;         ///< the destination planned to
    bool temporaryTarget = false;        ///< target on the free/undecided boundary
    /** The goal lies in known free space nearer an obstacle than the slowest
     * margin allows: the target is the reachable point nearest it. */
    bool nearestToGoal = false;
    bool marginBroken = false;  ///< fixed mode: no path with its own margin
};

/** The adaptive speed controller of Miura, Negishi, Shirai 2006 (000)
 * sections 3-5 (flow of Fig. 13), PAPER_NOTES M1:
 *  1. destination: the goal if it lies in known free space reachable by the
 *     slowest speed (or, for a known-free goal nearer an obstacle than that
 *     margin, the reachable point nearest it); else a temporary destination
 *     on the free/undecided boundary nearest the goal (section 3.3); beyond
 *     the paper, among the open frontier cells and the local map's edge, the
 *     one with the least path length to it + cost on from it (goalCost, or
 *     frontier_goal_weight x the straight line) + the switch cost;
 *  2. a path per candidate speed, obstacles grown by the robot radius + the
 *     speed's margin (planner behind IPathPlanner); beyond the paper, to a
 *     destination that is not temporary, a faster speed's search stops once
 *     its cost-to-go is known to exceed every slower speed's by more than
 *     gap_threshold (TPlannedPath::cutOff; the faster ones are then not
 *     planned): the rule below excludes it either way;
 *  3. the narrow-space rule on their cost-to-go (safeSpeedsByGap): the
 *     fastest safe speed owns the path;
 *  4. a faster speed is allowed too if its margin holds along the next
 *     lookahead_cycles cycles of that path (section 4.2);
 *  5. the fastest allowed speed with d / (v T) >= N (section 5), d measured
 *     along the path to where it comes within robot radius + margin (+ one
 *     cell) of a frontier cell; none: stop (reason Undecided).
 * Fixed mode (a comparison baseline): one speed, its own margin, no
 * undecided rule; with no path at its margin it plans with the robot radius
 * only and says so (marginBroken). */
class CAdaptiveSpeedController {
  public:
    CAdaptiveSpeedController(const TSpeedControlOptions& o, double robotRadius,
                             int necessaryObservations,
                             std::shared_ptr<const IPathPlanner> planner = nullptr);
    /** fixedIndex < 0: adaptive; else fixed at that candidate speed. */
    TSpeedDecision decide(const TPlanningField& field, const mrpt::math::TPose2D& robot,
                          const mrpt::math::TPoint2D& goal, int fixedIndex = -1,
                          const TTargetHints& hints = {}) const;
    const TSpeedControlOptions& options() const { return m_o; }
    int necessaryObservations() const { return m_N; }
    /** How decide() runs its independent parts (the per-speed plans to a
     * temporary destination; to the goal, or the point nearest it, they go
     * one after the other, slowest first, each bounding the next): empty
     * (the default) one after the other; a parallelFor needs a planner safe
     * to call from several threads (CGridPathPlanner is). The same decisions
     * either way. */
    void setParallelFor(common::TParallelFor parallel) {
        m_parallel = std::move(parallel);
    }
    /** [m] How near a way on (TPlanningField::wayOnDist) a candidate for a
     * temporary destination lies: the slowest speed's inflation + 2 cells of
     * a map of resolution `res`. A field for decide() needs wayOnReach >= it
     * (std::invalid_argument otherwise). */
    double wayOnBand(double res) const { return m_radius + m_o.margins.back() + 2 * res; }

    /** Step 1 alone: the destination to plan to, and whether it is temporary;
     * false when there is neither a reachable goal nor a reachable frontier. */
    bool chooseTarget(const TPlanningField& field, const mrpt::math::TPoint2D& start,
                      const mrpt::math::TPoint2D& goal, mrpt::math::TPoint2D& target,
                      bool& temporary, const TTargetHints& hints = {}) const;

  private:
    /** std::invalid_argument unless the field's wayOnDist reaches wayOnBand. */
    void checkWayOnReach(const TPlanningField& field) const;
    /** [m] the disc speed k plans with: the robot and that speed's margin. */
    double inflation(size_t k) const { return m_radius + m_o.margins[k]; }
    /** [m] how near d.target speed k's plan must end: a faster speed ends
     * where its larger margin lets it near a temporary target (placed on the
     * frontier for the slowest one); a destination is planned to exactly. */
    double targetTolerance(const TSpeedDecision& d, size_t k, double res) const {
        return d.temporaryTarget
                   ? inflation(k) - inflation(m_o.speeds.size() - 1) + 2 * res
                   : 0.0;
    }
    /** [m] d for speed k on path p: where its margin disc's front meets the
     * unknown (a path to a temporary target ends at the unknown anyway). */
    double undecidedAlong(const TPlannedPath& p, const TPlanningField& field,
                          const TSpeedDecision& d, size_t k) const;
    /** Every speed's plan to d.target into d.perSpeed (multi-speed planning,
     * section 4.1), given the slowest one's to a destination. */
    void planEverySpeed(const TPlanningField& field, const mrpt::math::TPoint2D& start,
                        TSpeedDecision& d,
                        const std::function<TPlannedPath()>& slowest) const;
    /** The fastest allowed speed whose undecided rule holds (section 4.2 and
     * eq. 6) into d, on d.path of speed `owner`. */
    void chooseSpeed(const TPlanningField& field, size_t owner, TSpeedDecision& d) const;
    TSpeedControlOptions m_o;
    double m_radius;
    int m_N;
    std::shared_ptr<const IPathPlanner> m_planner;
    common::TParallelFor m_parallel;
};
}  // namespace risknav::speed
