#pragma once
#include <risknav/geometry/polyline.h>
#include <risknav/speed/TPlanningField.h>

#include <mrpt/math/TPoint2D.h>

#include <limits>
#include <string>
#include <vector>

namespace risknav::speed {
/** A path of one candidate speed. */
struct TPlannedPath {
    std::vector<mrpt::math::TPoint2D> points;  ///< from the robot on (ego frame)
    double length = 0;                         ///< [m] along the points
    bool reached = false;                      ///< ends at the destination
    /** Cost-to-go (PAPER_NOTES M1): length + the straight-line distance left
     * from the path's end to the destination; +inf when not reached. */
    double costToGo = std::numeric_limits<double>::infinity();
    /** The search stopped at the caller's maxCost (beyond the paper, see
     * IPathPlanner::plan()): every path to the destination at this
     * inflation, and at any larger one, costs more than maxCost; reached =
     * false, costToGo = +inf, the points end at the nearest point to the
     * destination found so far (or are the start alone: not planned). */
    bool cutOff = false;
};

/** The planner behind the speed controller ((000) section 3.3: "any planner
 * works"): a path from start to within `goalTolerance` of the goal whose
 * every point keeps a clearance of at least `inflation` (robot size + the
 * speed's margin) from non-free cells. A complete planner: when the goal
 * cannot be reached, costToGo is +inf (the path shown ends at the reachable
 * point nearest the goal, reached = false). A robot already closer than `inflation` to a
 * non-free cell has no path at that inflation (costToGo = +inf: the speed's margin is
 * broken now), unless `escape`: then, near the start, it may move with the clearance it
 * has (never nearer a non-free cell than the start; half a cell of rounding
 * only when there is no other way out), so that the slowest speed can get out.
 * Optimal: the path's cost-to-go is the least among the planner's paths at
 * that inflation, so a larger inflation (fewer cells, no escape) never gives
 * a lower one (to within two cells: the path starts at the robot's own
 * position and ends at the destination's, not at cell centres).
 *
 * maxCost (beyond the paper, a speed-up for the gap rule, which needs a
 * faster speed's cost-to-go only while it is within gap_threshold of the
 * slower ones'): the planner may stop once it knows every path costs more
 * than maxCost, and then says so (TPlannedPath::cutOff). +inf: never. */
class IPathPlanner {
  public:
    virtual ~IPathPlanner() = default;
    virtual TPlannedPath plan(
        const TPlanningField& field, const mrpt::math::TPoint2D& start,
        const mrpt::math::TPoint2D& goal, double inflation, double goalTolerance,
        bool escape, double maxCost = std::numeric_limits<double>::infinity()) const = 0;
    virtual std::string name() const = 0;
};

/** The cells a robot starting at cell (si, sj) may enter at an inflation:
 * clearance >= inflation; with `escape`, within inflation + 2 cells of the
 * start also cells no nearer a non-free cell than the start (half a cell of
 * rounding only when that gives no way out). The one rule of the planner and
 * of the target flood. */
class CTraversable {
  public:
    CTraversable(const TPlanningField& field, int si, int sj, double inflation,
                 bool escape);
    bool operator()(int i, int j) const;
    /** The start cell itself keeps the inflation. */
    bool startKeepsInflation() const { return m_startClear >= m_inflation; }

  private:
    const TPlanningField& m_field;
    int m_si, m_sj;
    double m_inflation, m_startClear, m_escapeRadius;
    bool m_escape;
    double m_slack = 0;  ///< [m] rounding allowed on the escape
};

/** A* on the grid's cells, 8-connected, octile heuristic (exact for the
 * cost of its moves). With a finite maxCost it stops when the least
 * f = g + h left to expand exceeds maxCost + 2 cells + a tenth of the
 * tolerance (a path's cost-to-go differs from its cells' g by less than
 * that: its ends are the robot's and the destination's own positions). */
class CGridPathPlanner : public IPathPlanner {
  public:
    TPlannedPath plan(
        const TPlanningField& field, const mrpt::math::TPoint2D& start,
        const mrpt::math::TPoint2D& goal, double inflation, double goalTolerance,
        bool escape,
        double maxCost = std::numeric_limits<double>::infinity()) const override;
    std::string name() const override { return "grid_astar"; }
};

/** d of (000) section 3: the along-path distance [m] from the path's start
 * to its first point where the front of the robot's margin disc (radius
 * `reach` = robot radius + the speed's margin) touches the unknown: one of
 * five probes on the front of that circle (0, +-22.5, +-45 deg from the
 * path's direction) lies on an undecided cell. Only the front:
 * the unknown behind and beside a robot that has not looked there yet (a
 * laser mounted ahead of the centre never sees beside the robot at the
 * start) is not where it is going. +inf if no point does. */
double distanceToUndecided(const TPlannedPath& path, const TPlanningField& field,
                           double reach);

/** Whether every point of the path within `distance` [m] of its start keeps
 * a clearance of at least `inflation` ((000) section 4.2 check). */
bool clearanceHoldsAhead(const TPlannedPath& path, const TPlanningField& field,
                         double inflation, double distance);
/** Pure pursuit's look-ahead point on a path (geometry::lookaheadOnPolyline()
 * on the field's clearance, chords sampled every half cell). Beyond the paper (its robot
 * follows its arcs); risknav-explore's controller steers to it and
 * CRiskAwareReactiveNav gives it to MRPT's engine as its local target.
 * Paths of fewer than 2 points: both 0. */
using geometry::TLookahead;
TLookahead lookaheadPoint(const TPlannedPath& path, const TPlanningField& field,
                          const mrpt::math::TPoint2D& from, double lookahead);
}  // namespace risknav::speed
