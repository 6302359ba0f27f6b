#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/mapping/CDistanceField.h>
#include <risknav/planning/grid_search.h>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace risknav::planning {
/** One global plan. */
struct TGlobalPlan {
    bool found = false;
    std::vector<mrpt::math::TPoint2D> points;  ///< world [m], from the start to the goal
    double length = 0;                         ///< [m]
    double cost = 0;                           ///< [m x cost per metre] (the search's)
    double minClearance = 0;  ///< [m] robot centre to the nearest obstacle cell on it
    /** No path: start_blocked | goal_blocked | narrow_gap | disconnected. */
    std::string failure;
    std::string reason;  ///< one sentence for the summary ("" when found)
    double ms = 0;       ///< [ms] wall time of the plan
    size_t expanded = 0;
};

/** What a route chooser made of the candidates of one target. */
struct TRouteChoice {
    size_t chosen = 0;           ///< index into the candidates
    std::vector<double> score;   ///< per candidate (risk: U of eq. 30; +inf: excluded)
    std::vector<double> length;  ///< [m] per candidate
    std::string reason;          ///< why the chosen one
};

/** A replan and why. */
struct TReplanEvent {
    double t = 0;     ///< [s] the navigator's clock
    std::string why;  ///< new_target | blocked | strayed | pose_jump
    double x = 0, y = 0;
    double length = 0;  ///< [m] of the new plan (0: none found)
    double ms = 0;
};

/** risknav-navigate's global planner on a known map (beyond the papers:
 * they assume a route; a reactive engine alone does not find a way round a
 * wall). A least-cost path for the disc MRPT's engine plans for, on the
 * map's cells: 8-connected grid A* (gridAStar()) over cells whose clearance
 * (CDistanceField, the map's own obstacle rule) holds the disc, each metre
 * costing 1 + clearance_weight * ((soft - c) / (soft - disc))^2 for a
 * clearance c below soft = disc + clearance_soft (so the path keeps to the
 * middle of a corridor and off door posts, and still takes a door the disc
 * fits through). Grid A* rather than a sampling planner or a visibility
 * graph: exact (optimal on its graph, tested against Bellman-Ford), complete
 * on the grid, and it works on any occupancy map as it is (SLAM speckle,
 * unknown cells), where the GVG of the risk evaluator needs cleaning.
 *
 * Following: MRPT's engine is aimed at the point `lookahead` ahead on the
 * plan (geometry::lookaheadOnPolyline()); the plan is made again when the
 * target changes, when sensed obstacles the map does not hold lie on the
 * way ahead (people, clutter: remembered for obstacle_memory seconds, and
 * forgotten where a later scan sees through them), when the robot strays
 * from it, and when the pose jumps (a localization correction). */
class CGlobalPlanner {
  public:
    /** [GlobalPlanner]: every key is declared once, in declare(). */
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "GlobalPlanner"; }
        /** [m] a way keeps this beyond the engine's disc (0: a gap the
         * engine's shape fits is planned through; MRPT's engine passed the
         * Willow Garage map's 0.75 m doors with a 0.66 m shape, and crept at
         * mm/s between the TurtleBot3 arena's pillars as far apart) */
        double margin = 0;
        double clearance_soft = 0.5;  ///< [m] beyond the disc, nearer costs more
        double clearance_weight = 4;  ///< cost per metre at the disc's edge = 1 + this
        double lookahead = 2.0;       ///< [m] MRPT's engine aims this far ahead
        double stray_distance = 1.0;  ///< [m] from the plan: replan
        double pose_jump = 0.5;       ///< [m] in one cycle: replan
        double check_ahead = 4.0;     ///< [m] of the plan checked for sensed obstacles
        double obstacle_memory = 30;  ///< [s] a sensed obstacle is kept
        /** Candidates of distinct homotopy classes the route chooser
         * (global_planner = risk) picks from, the least-cost way first. */
        int candidates = 3;
        double replan_interval = 1.0;  ///< [s] at least between replans for blocking
        /** known: the map given to setMap() is the world's (its obstacles
         * planned round, sensed ones remembered obstacle_memory seconds);
         * built: the robot does not know the world (M1's setting): setMap()
         * gives only the extent, every cell counts as free until sensed
         * (the free-space assumption of planning in unknown terrain), and a
         * sensed obstacle stays until a later beam passes through it. */
        std::string map = "known";

      protected:
        void declare(Visitor& v) override;
    };
    TOptions options;  ///< [GlobalPlanner]

    /** The map to plan on, with its obstacle rule, and the radius [m] of the
     * disc the engine plans for (a way keeps options.margin more). Computes
     * the clearance and cost grids once. */
    void setMap(const mrpt::maps::COccupancyGridMap2D& grid,
                const mapping::TObstacleRule& rule, double discRadius);
    bool hasMap() const { return m_fine.cost.w > 0; }
    const mapping::CDistanceField& field() const { return m_field; }
    double discRadius() const { return m_disc; }

    /** A plan from `from` to `to` on the map, and (`withSensed`) around the
     * sensed obstacles remembered now. A start or goal nearer an obstacle
     * than the disc may leave or reach it through cells no nearer than
     * itself. */
    TGlobalPlan plan(const mrpt::math::TPoint2D& from, const mrpt::math::TPoint2D& to,
                     bool withSensed = false) const;

    /** Up to k least-cost ways on the map from `from` to `to`, each of
     * another homotopy class (geometry::sameHomotopy()): the first is
     * plan(); each next one is the least-cost way with the earlier ones'
     * corridors (the disc + 0.3 m about them, beyond the disc + 1 m of the
     * ends) closed. Fewer when no other class exists. */
    std::vector<TGlobalPlan> alternatives(const mrpt::math::TPoint2D& from,
                                          const mrpt::math::TPoint2D& to, int k) const;
    /** A way as straight legs (Douglas-Peucker, 0.1 m): no leg passes
     * nearer an obstacle than the disc (or than the nearer of its ends,
     * where a start or goal lies nearer). What a route evaluator drives. */
    std::vector<mrpt::math::TPoint2D> legs(const TGlobalPlan& way) const;

    /** Picks the route to a new target among alternatives() (nullptr: the
     * least-cost way): global_planner = risk, M2's U. */
    std::function<TRouteChoice(const std::vector<TGlobalPlan>&)> routeChooser;
    /** Every choice made, one per new target (with a routeChooser). */
    const std::vector<TRouteChoice>& choices() const { return m_choices; }

    /** Sensed points (robot frame of `pose`) at time `now` [s]: those the
     * map does not explain are remembered; cells the beams crossed are
     * forgotten. */
    void addSensed(const mrpt::math::TPose2D& pose,
                   const std::vector<mrpt::math::TPoint2D>& robotFrame, double now);

    /** The remembered sensed obstacle cells (each its point nearest the
     * robot, half a cell short of its centre) within `reach`
     * [m] of `pose`, in its robot frame: what the robot saw beside or
     * behind it, outside its laser's view now. */
    std::vector<mrpt::math::TPoint2D> sensedNear(const mrpt::math::TPose2D& pose,
                                                 double reach) const;

    /** Before each engine step: replans as needed for the robot at `pose`
     * going to `target` at time `now`. Returns the replan made (if any). */
    std::optional<TReplanEvent> update(const mrpt::math::TPose2D& pose,
                                       const mrpt::math::TPoint2D& target, double now);
    /** The plan being followed (found = false: none for this target). */
    const TGlobalPlan& current() const { return m_plan; }
    /** The target the current plan leads to. */
    std::optional<mrpt::math::TPoint2D> currentTarget() const { return m_target; }
    /** The point lookahead ahead of `pose` on the plan; nullopt without one. */
    std::optional<mrpt::math::TPoint2D> guidePoint(const mrpt::math::TPose2D& pose) const;
    /** [m] what is left of the plan from `pose` (+inf without one). */
    double remainingLength(const mrpt::math::TPose2D& pose) const;
    /** The plan's point nearest `pose`, searched from the progress made on
     * over the next few metres (not the whole plan: one that turns round a
     * thin wall passes near itself). 0 without a plan. */
    size_t nearestIndex(const mrpt::math::TPose2D& pose) const;

    const std::vector<TReplanEvent>& replans() const { return m_events; }
    /** Before a new run: no target, plan, replans, choices or sensed
     * obstacles (the map's grids stay). */
    void resetFollowing();

  private:
    /** The cells one plan is made on: the map's own (k = 1) or blocks of
     * k x k of them. */
    struct TLevel {
        int k = 1;
        TCostGrid cost;
        /** [m] cell centre to the nearest obstacle cell's edge (coarse:
         * the least of its own cells') */
        std::vector<float> clearEdge;
    };
    TLevel m_fine, m_coarse;
    bool planOn(
        const TLevel& level, const mrpt::math::TPoint2D& from,
        const mrpt::math::TPoint2D& to, bool withSensed, TGlobalPlan& p,
        const std::vector<std::vector<mrpt::math::TPoint2D>>* avoid = nullptr) const;
    std::vector<TRouteChoice> m_choices;
    mapping::CDistanceField m_field;
    double m_disc = 0;
    mutable TCostGrid m_work;  // the map and the sensed obstacles
    /** [s] when a cell was last sensed as an obstacle, since m_timeBase (a
     * float of clock time, ~1.7e9 s, resolves only 128 s). */
    std::vector<float> m_seenAt;
    std::optional<double> m_timeBase;  ///< the clock at the run's first sensing
    float sinceBase(double now) const { return float(now - m_timeBase.value_or(now)); }
    std::vector<int32_t> m_seenCells;
    std::optional<mrpt::math::TPoint2D> m_target;
    std::optional<mrpt::math::TPose2D> m_lastPose;
    double m_lastBlockedReplan = -1e18;
    TGlobalPlan m_plan;
    std::vector<TReplanEvent> m_events;
    float costOf(double clearanceEdge) const;
    bool liveSeen(size_t i, double now) const {
        return m_seenAt[i] != kNeverSeen &&
               (m_keepSeen ||
                double(sinceBase(now)) - double(m_seenAt[i]) <= options.obstacle_memory);
    }
    static constexpr float kNeverSeen = -std::numeric_limits<float>::infinity();
    bool m_keepSeen = false;  ///< map = built: sensed obstacles are the map
    /** [m] per cell of L: its centre to the nearest live sensed cell's edge
     * (the least over a coarse cell's own cells, as its clearEdge), +inf
     * where that is beyond disc + clearance_soft (no cost). */
    void sensedClearance(const TLevel& L, std::vector<float>& out) const;
    /** [m] added to every sensed clearance while planning: 0, or one cell
     * when no way keeps the whole disc off the sensed points, or (map =
     * built) when such a way is over 1.5 times (+ 1 m) longer than the way
     * within a cell of them (a laser's range noise puts a surface's points
     * up to a cell in front of it, so a gap the disc fits by centimetres
     * senses a cell narrower). */
    mutable double m_sensedSlack = 0;
    double m_planSlack = 0;  ///< the slack the current plan was made with
    mutable std::vector<float> m_sensedEdge;
    mutable std::vector<uint8_t> m_sensedMask;
    mutable std::vector<int32_t> m_sensedD2;
    bool blockedAhead(const mrpt::math::TPose2D& pose, double now) const;
    double m_now = 0;
    size_t m_progress = 0;  ///< the plan's point the robot was nearest last
};
}  // namespace risknav::planning
