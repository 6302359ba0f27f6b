#pragma once
#include <risknav/common/CIniConfig.h>
#include <risknav/common/grid_io.h>
#include <risknav/risk/CGvgRoutes.h>
#include <risknav/risk/CObstacleField.h>
#include <risknav/risk/path_risk.h>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPoint2D.h>

#include <memory>
#include <string>
#include <vector>

namespace risknav::risk {
/** Ranks candidate routes from start to goal by their integrated risk of
 * collision under odometry drift (Irie, Nagatani, Gofuku (001); PAPER_NOTES
 * M2), for every subset of sensing points a route may visit (like the paper's
 * Table 1). Candidates: [RouteN] sections of the config and/or the k
 * shortest GVG routes. Config sections: [RiskEval] [Odometry] [RouteN]
 * [SensingPointN], documented in config/risknav-risk-eval.ini. */
class CRiskEvaluator {
  public:
    struct TRoute {
        std::string name;
        std::vector<mrpt::math::TPoint2D> waypoints;  ///< from start to goal
        bool fromGvg = false;
    };
    /** One row of the table: a route driven with one subset of sensing points. */
    struct TRow {
        size_t route = 0;
        std::vector<size_t> sensing;             ///< indices into sensingPoints
        std::vector<mrpt::math::TPoint2D> path;  ///< route with the detours
        bool feasible = true;  ///< false: a detour to a sensing point crosses an obstacle
        TRiskResult result;
        bool excluded = false;
        std::string reason;  ///< why excluded ("" if not)
    };

    // ---- options (loaded by loadFromConfigFile)
    common::TMapSourceOptions mapSource;
    CObstacleField::TOptions fieldOptions;
    TRiskOptions riskOptions;
    CGvgRoutes::TOptions gvgOptions;
    mrpt::math::TPoint2D start, goal;
    double uThreshold =
        0;  ///< exclude rows whose max u exceeds this (section 5.3); 0: off
    int maxSensingSubset = 2;    ///< subsets of sensing points up to this size
    int gvgRoutes = 3;           ///< k shortest GVG routes (0: only [RouteN])
    double ellipseInterval = 2;  ///< [m] between drawn ellipses
    std::vector<TRoute> configRoutes;
    std::vector<TSensingPoint> sensingPoints;

    /** Loads and validates every section and the map: start/goal off the map
     * or inside an obstacle, sensing points inside obstacles, bad numbers,
     * no candidates at all: CBadInputError before any output. */
    void loadFromConfigFile(const common::CIniConfig& c);

    /** Builds the candidates and evaluates every route x sensing subset. */
    void evaluate();

    const mrpt::maps::COccupancyGridMap2D& grid() const { return m_grid; }
    const CObstacleField& field() const { return *m_field; }
    const CGvgRoutes* gvg() const { return m_gvg.get(); }
    const std::vector<TRoute>& routes() const { return m_routes; }
    const std::vector<TRow>& rows() const { return m_rows; }
    /** Index of the best row (lowest U among the rows not excluded), -1 if none. */
    long best() const { return m_best; }
    /** "none" or "SP1+SP2". */
    std::string sensingName(const TRow& r) const;
    /** The row of a route without sensing. */
    const TRow& plainRow(size_t route) const;

  private:
    mrpt::maps::COccupancyGridMap2D m_grid;
    std::unique_ptr<CObstacleField> m_field;
    std::unique_ptr<CGvgRoutes> m_gvg;
    std::vector<TRoute> m_routes;
    std::vector<TRow> m_rows;
    long m_best = -1;
};

}  // namespace risknav::risk
