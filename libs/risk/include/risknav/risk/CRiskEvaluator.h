#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/TOdometryOptions.h>
#include <risknav/common/TRobotOptions.h>
#include <risknav/common/grid_io.h>
#include <risknav/mapping/TObstacleRule.h>
#include <risknav/risk/CGvgRoutes.h>
#include <risknav/risk/CObstacleField.h>
#include <risknav/risk/TPropagationOptions.h>
#include <risknav/risk/TRouteOptions.h>
#include <risknav/risk/TSensingPointOptions.h>
#include <risknav/risk/path_risk.h>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPoint2D.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace risknav::risk {
/** Ranks candidate routes from start to goal by their integrated risk of
 * collision under odometry drift (Irie, Nagatani, Gofuku (001); PAPER_NOTES
 * M2), for every subset of sensing points a route may visit (like the paper's
 * Table 1). Candidates: [RouteN] sections of the config, the k shortest GVG
 * routes (the paper's), and the least-cost grid ways of distinct homotopy
 * classes for the robot disc (planning::CGlobalPlanner::alternatives(),
 * beyond the paper: a grid way exists wherever the disc fits, on SLAM maps
 * whose GVG breaks up or weaves between speckles). Config sections: [RiskEval] (options),
 * [Robot] (robot: its radius grows the obstacles), [Odometry] (odometry + propagation),
 * [RouteN] (configRoutes), [SensingPointN] (sensingPoints), documented in
 * config/risknav-risk-eval.ini. */
class CRiskEvaluator {
  public:
    /** @name The work of one run, bounded (unbounded, a tiny speed grows memory
     * as 1/speed; 20 sensing points with max_sensing_subset = 6 ran 146 s and
     * wrote 60,467 files). validate() checks what the config alone decides
     * (candidates, rows); evaluate() checks the propagation steps of the rows'
     * paths before it propagates any. Exceeding one: CBadInputError (exit 2)
     * naming the key to change.
     * @{ */
    /** Candidate routes: [RouteN] sections + gvg_routes + grid_routes. */
    static constexpr size_t kMaxRoutes = 100;
    /** Rows = candidates x sensing subsets (sum_{k <= max_sensing_subset} C(n, k)). */
    static constexpr size_t kMaxRows = 1000;
    /** Propagation steps of all rows together (motionStepCount()): each keeps
     * at most one u sample (~200 bytes) per straight step. */
    static constexpr double kMaxSteps = 5e6;
    /** Trajectory steps = propagation steps x trajectories driven (1 linear,
     * 2n unscented, 2n^2 + 1 cubature5, `samples` sampled; n = 3 per_step, 6
     * systematic): 30-100 ns each (bench_risk), so at most ~20 s. */
    static constexpr double kMaxTrajectorySteps = 2e8;
    /** @} */

    /** The [RiskEval] keys: the map, which of its cells are obstacles, start
     * and goal, the candidates and the evaluation. Every key is declared
     * once, in declare() (the map's, the obstacle rule's and gvg's by
     * including them). */
    struct TOptions : public common::CDeclaredOptions {
        common::TMapSourceOptions map;     ///< map_* keys
        mapping::TObstacleRule obstacles;  ///< occupied_threshold ... outside_is_obstacle
        CGvgRoutes::TOptions gvg;  ///< gvg_separation_ratio, gvg_simplify_tolerance
        mrpt::math::TPoint2D start{std::nan(""), std::nan("")};  ///< [m] required
        mrpt::math::TPoint2D goal{std::nan(""), std::nan("")};   ///< [m] required
        double u_threshold =
            0;  ///< exclude rows whose max u exceeds this (section 5.3); 0: off
        int max_sensing_subset = 2;  ///< subsets of sensing points up to this size
        int gvg_routes = 3;          ///< k shortest GVG routes (0: none)
        /** Least-cost grid ways of distinct homotopy classes for the robot
         * disc (0: none); the first is the least-cost way (plan()). */
        int grid_routes = 3;
        double ellipse_interval = 2;  ///< [m] between drawn ellipses
        double eval_step = 0.05;      ///< [m] D_max / u sampling along the path
        uint64_t seed = 1;  ///< of [Odometry] propagation = sampled; --seed overrides

        TOptions() {
            section = "RiskEval";
            map.section = obstacles.section = gvg.section = section;
        }

      protected:
        void declare(Visitor& v) override;
        /** The goal differs from the start. */
        void validateRules() const override;
    };

    struct TRoute {
        std::string name;
        std::vector<mrpt::math::TPoint2D> waypoints;  ///< from start to goal
        /** Where it came from: config ([RouteN]), gvg or grid. */
        std::string source = "config";
    };
    /** One row of the table: a route driven with one subset of sensing points. */
    struct TRow {
        size_t route = 0;
        std::vector<size_t> sensing;             ///< indices into sensingPoints
        std::vector<mrpt::math::TPoint2D> path;  ///< route with the detours
        bool feasible = true;  ///< false: a detour to a sensing point crosses an obstacle
        /** result.samples are kept for the plain row of each route and the best
         * row of each route only (their cov_*.csv, images); the others are
         * summarised in the table (U, u_max, ...). */
        TRiskResult result;
        bool excluded = false;
        std::string reason;  ///< why excluded ("" if not)
    };

    // ---- options: every section of the config
    TOptions options;                         ///< [RiskEval]
    common::TRobotOptions robot;              ///< [Robot] (radius)
    common::TOdometryOptions odometry;        ///< [Odometry] wheels, sigmas, model
    TPropagationOptions propagation;          ///< [Odometry] tau, speed, sigmas
    std::vector<TRouteOptions> configRoutes;  ///< [Route1], [Route2], ...
    std::vector<TSensingPointOptions> sensingPoints;  ///< [SensingPoint1], ...

    /** Reads every section (MRPT style: each options struct loads its own
     * keys, then validate()), rejects unknown sections and keys, then
     * prepare(). Any problem: CBadInputError naming the file, before any output. */
    void loadFromConfigFile(const common::CIniConfig& c);
    /** Writes every key of every section (config_effective.ini). */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** Every options struct's validate(), and the rules between them (at least
     * one candidate, unique sensing point names). Throws CConfigKeyError. */
    void validate() const;
    /** @name Output file names: a route's or sensing point's name with every
     * byte but letters, digits, '-' and '_' made '_' (a '+' too: it joins the
     * sensing points of a row). validate() refuses two routes (config or GVG,
     * or a route and the best row's image) or two sensing points whose names
     * give one file name, and names too long for the file system.
     * @{ */
    static std::string fileNamePart(const std::string& name);
    /** cov_<route>[+<sensing point>...].csv */
    static std::string covFileName(const std::string& route,
                                   const std::vector<std::string>& sensing);
    /** ellipses_<route>.png ("best" is the best row's image). */
    static std::string ellipsesFileName(const std::string& route);
    /** The name of the k-th GVG route (1-based). */
    static std::string gvgRouteName(size_t k);
    /** The name of the k-th grid way (1-based). */
    static std::string gridRouteName(size_t k);
    /** Throws CBadInputError naming the key when a file this run writes into
     * `outDir` would have a path longer than PATH_MAX. */
    void checkOutputPaths(const mrpt::config::CConfigFileBase& c,
                          const std::string& outDir) const;
    /** @} */

    /** validate(), loads the map and grows its obstacles, and checks start,
     * goal, sensing points and route points against it (off the map, inside a
     * grown obstacle: CConfigKeyError). Run again after changing options. */
    void prepare();

    /** Builds the candidates and evaluates every route x sensing subset
     * (prepare() first if it has not run). Throws CBadInputError (naming the
     * config file when loaded from one) when the rows need more than kMaxSteps
     * propagation steps or kMaxTrajectorySteps trajectory steps. */
    void evaluate();

    /** What evaluatePathRisk() is given (makeRiskOptions). */
    TRiskOptions riskOptions() const;
    const mrpt::maps::COccupancyGridMap2D& grid() const { return m_grid; }
    const CObstacleField& field() const { return *m_field; }
    const CGvgRoutes* gvg() const { return m_gvg.get(); }
    const std::vector<TRoute>& routes() const { return m_routes; }
    const std::vector<TRow>& rows() const { return m_rows; }
    /** With grid_routes > 0 and no grid way: why none exists for the robot
     * disc (planning::TGlobalPlan::failure and reason: start_blocked,
     * goal_blocked, narrow_gap, disconnected); empty otherwise. */
    const std::string& noWayFailure() const { return m_noWayFailure; }
    const std::string& noWayReason() const { return m_noWayReason; }
    /** Index of the best row (lowest U among the rows not excluded), -1 if none. */
    long best() const { return m_best; }
    /** "none" or "SP1+SP2". */
    std::string sensingName(const TRow& r) const;
    /** The row of a route without sensing. */
    const TRow& plainRow(size_t route) const;

    /** Propagation and trajectory steps of the last evaluate(). */
    double propagationSteps() const { return m_steps; }
    double trajectorySteps() const { return m_trajSteps; }
    /** Trajectories one propagation step drives (1 for linear). */
    size_t trajectoriesPerStep() const;
    /** Number of sensing subsets evaluated per route. */
    double sensingSubsets() const;

  private:
    std::string m_where;  // "file.ini: " when loaded from a file
    double m_steps = 0, m_trajSteps = 0;
    mrpt::maps::COccupancyGridMap2D m_grid;
    std::unique_ptr<CObstacleField> m_field;
    std::unique_ptr<CGvgRoutes> m_gvg;
    std::vector<TRoute> m_routes;
    std::vector<TRow> m_rows;
    long m_best = -1;
    std::string m_noWayFailure, m_noWayReason;
};

}  // namespace risknav::risk
