#pragma once
#include <risknav/common/CIniConfig.h>
#include <risknav/common/TRobotOptions.h>
#include <risknav/geometry/CSegmentIndex.h>
#include <risknav/viewpoint/TPolygonWorld.h>
#include <risknav/viewpoint/TViewpointPlanOptions.h>
#include <risknav/viewpoint/observation_model.h>
#include <risknav/viewpoint/viewpoint_greedy.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace risknav::viewpoint {
/** An observation with its worst-case errors and how far it lets the robot go. */
struct TStrategyChoice {
    TObservation obs;
    TWorstCase err;
    double reach = -1;  ///< [m] m_max after observing (eq. (2)); < 0: unusable here
};

/** What can be observed at one path sample: the best observation overall
 * (largest m_max, i.e. the smallest E_max at the distance the robot then
 * travels: eq. (1)) and the best of each strategy (003 Table 1's rows). */
struct TPointEvaluation {
    std::optional<TStrategyChoice> best;
    std::array<std::optional<TStrategyChoice>, 3> perStrategy;  ///< A, B, C
    size_t observations = 0;  ///< observations enumerated
    size_t degenerate =
        0;  ///< of which near-singular (no solution for some sign combination)
};

struct TPlannedViewpoint {
    TPathSample at;
    TPointEvaluation eval;
    double m = 0;  ///< [m] distance to the next viewpoint (or the goal)
};

/** One (S, path) of the sweep: 004 Tables II/III's row, plus its viewpoints. */
struct TPlanRow {
    double S = 0;     ///< [m] safety margin
    size_t rank = 0;  ///< 0: the shortest path at this S
    int route = 0;    ///< homotopy class, 1 = the class of the shortest path overall
    std::vector<mrpt::math::TPoint2D> path;
    double length = 0;      ///< [m]
    double minAllowed = 0;  ///< [m] the smallest allowed error along the path (>= S)
    bool feasible = false;
    double reach = 0;  ///< [m] arc length where an infeasible plan fails
    mrpt::math::TPoint2D failAt;
    std::vector<TPlannedViewpoint> viewpoints;
    size_t evaluations = 0;  ///< strategy evaluations spent
    size_t degenerate = 0;   ///< near-singular observations met (reported, never used)
};

struct TSweepPoint {
    double S = 0;
    bool startFree = false, goalFree = false;
    size_t nodes = 0, edges = 0;                 ///< visibility graph
    std::vector<geometry::TSegment> graphEdges;  ///< for the picture
    std::vector<TPlanRow> rows;
};

/** 004 section II's ranking of feasible plans: the shortest first, then the
 * fewest viewpoints. Plans no longer than the shortest one + tolerance [m]
 * count as equally long (compared with the shortest, not with each other, so
 * equal-length steps do not chain); among them the fewest viewpoints win,
 * then the larger S, then the shorter. nullptr when none is feasible. */
const TPlanRow* bestPlan(const std::vector<const TPlanRow*>& rows, double tolerance);

/** Path and viewpoint planning with multiple observation strategies
 * (Yamashita et al. 004/003, M4): for each safety margin S, the C-obstacles
 * grown by R + S, the visibility graph, the k shortest paths, and greedy
 * viewpoints on each; the optimal plan is the shortest feasible path, then
 * the one with the fewest viewpoints (004 section II), then the larger S. */
class CViewpointPlanner {
  public:
    TViewpointPlanOptions options;
    TCameraOptions camera;
    common::TRobotOptions robot;

    /** Reads [ViewpointPlan], [Camera], [Robot] (unknown sections and keys
     * are errors), loads and checks the world; start or goal inside an
     * obstacle or within the robot radius of one is bad input (named by its
     * key). Throws CBadInputError. */
    void loadFromConfigFile(const common::CIniConfig& c);
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** A world built in code (tests, benchmarks); options must be set. */
    void setWorld(TPolygonWorld w);

    /** The whole sweep. */
    void plan();

    const TPolygonWorld& world() const { return m_world; }
    const std::vector<mrpt::math::TPoint2D>& obstacleReferences() const { return m_refs; }
    const std::vector<TSweepPoint>& sweep() const { return m_sweep; }
    /** (sweep index, row index) of the optimal plan; nullopt: none feasible. */
    std::optional<std::pair<size_t, size_t>> optimal() const { return m_optimal; }
    size_t routeCount() const { return m_routeCount; }

    /** Evaluates every observation at sample i of a path (worst cases,
     * m_max). bestOnly: an observation's sign combinations stop as soon as
     * it cannot beat the best found so far (the same best, much faster; the
     * per-strategy bests and the degenerate count are then incomplete). */
    TPointEvaluation evaluate(const std::vector<TPathSample>& samples, size_t i,
                              bool bestOnly = false) const;
    /** Allowed error at a point: distance to the nearest obstacle minus R. */
    double allowedError(double x, double y) const;
    /** Plans the viewpoints of one path at margin S (used by plan()). */
    TPlanRow planPath(const std::vector<mrpt::math::TPoint2D>& path, double S) const;

    /** Monte Carlo check of a plan: at every viewpoint, `draws` image errors
     * drawn uniformly within +-du/+-dr, the pose re-solved, and the error at
     * the next viewpoint |dp| + 2 m sin(|dphi|/2) compared with E_max(m).
     * Returns the largest ratio (<= 1: the worst-case bound held). */
    struct TMonteCarlo {
        size_t draws = 0, failures = 0;
        double maxRatioPos = 0, maxRatioTotal = 0;
    };
    TMonteCarlo monteCarlo(const TPlanRow& row, size_t draws, uint64_t seed) const;

    /** Work limits (exit 2 naming the key that would exceed them): visibility
     * graph nodes (the pair loop is quadratic in them) and samples per path. */
    static constexpr size_t kMaxGraphNodes = 6000;
    static constexpr double kMaxSamplesPerPath = 2e6;
    /** The corner nodes corner_segments gives the world's convex corners. */
    size_t cornerNodeCount() const;

  private:
    TPolygonWorld m_world;
    geometry::CSegmentIndex m_index;
    std::vector<mrpt::math::TPoint2D> m_refs;
    std::vector<TSweepPoint> m_sweep;
    std::optional<std::pair<size_t, size_t>> m_optimal;
    size_t m_routeCount = 0;
    std::string m_where;

    void prepare();
    void assignRoutes();
};

}  // namespace risknav::viewpoint
