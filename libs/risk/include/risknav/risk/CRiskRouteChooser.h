#pragma once
#include <risknav/planning/CGlobalPlanner.h>
#include <risknav/risk/CObstacleField.h>
#include <risknav/risk/TPropagationOptions.h>
#include <risknav/risk/path_risk.h>

#include <memory>

namespace risknav::risk {
/** global_planner = risk: M2 (Irie, Nagatani, Gofuku) as the global
 * planner's route chooser. Each candidate (CGlobalPlanner::alternatives(),
 * the best way of each of up to [GlobalPlanner] candidates homotopy classes;
 * the least-cost way always among them) is driven in the risk evaluator's
 * model: simplified to straight legs (Douglas-Peucker, 0.1 m, no leg nearer
 * an obstacle than the planner's disc), the odometry covariance propagated
 * along it from the start's ([Odometry] sigmas, propagation), and scored by
 * U = integral of 1 / D_max^2 (eqs. 28-30, evaluatePathRisk()). The lowest
 * finite U is driven. Beyond the paper: its candidates are GVG routes; here
 * they are grid ways of distinct classes, which survive SLAM speckle. */
class CRiskRouteChooser {
  public:
    CRiskRouteChooser(const mrpt::maps::COccupancyGridMap2D& grid,
                      const mapping::TObstacleRule& rule, double robotRadius,
                      const TRiskOptions& riskOptions,
                      const planning::CGlobalPlanner& planner);
    planning::TRouteChoice choose(
        const std::vector<planning::TGlobalPlan>& candidates) const;

  private:
    CObstacleField m_field;
    TRiskOptions m_risk;
    const planning::CGlobalPlanner& m_planner;
};
}  // namespace risknav::risk
