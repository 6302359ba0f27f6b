#include <risknav/risk/CRiskRouteChooser.h>

#include <cmath>
#include <cstdio>
#include <limits>

namespace risknav::risk {
CRiskRouteChooser::CRiskRouteChooser(const mrpt::maps::COccupancyGridMap2D& grid,
                                     const mapping::TObstacleRule& rule,
                                     double robotRadius, const TRiskOptions& riskOptions,
                                     const planning::CGlobalPlanner& planner)
    : m_field(grid, rule, robotRadius), m_risk(riskOptions), m_planner(planner) {}

planning::TRouteChoice CRiskRouteChooser::choose(
    const std::vector<planning::TGlobalPlan>& cands) const {
    planning::TRouteChoice out;
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < cands.size(); i++) {
        double U = std::numeric_limits<double>::infinity();
        if (cands[i].found) {
            const auto r =
                evaluatePathRisk(m_planner.legs(cands[i]), {}, m_field, m_risk);
            if (r.failure.empty() && !r.blocked)
                U = r.U;
        }
        out.score.push_back(U);
        out.length.push_back(cands[i].length);
        if (U < best)
            best = U, out.chosen = i;
    }
    char b[160];
    if (std::isfinite(best))
        std::snprintf(b, sizeof(b), "the lowest U (%.4g) of %zu ways of distinct classes",
                      best, cands.size());
    else
        std::snprintf(b, sizeof(b),
                      "no way of the %zu has a finite U: the least-cost way",
                      cands.size());
    out.reason = b;
    if (!std::isfinite(best))
        out.chosen = 0;
    return out;
}
}  // namespace risknav::risk
