#pragma once
#include <risknav/common/CAppRunner.h>
#include <risknav/common/COutputDir.h>
#include <risknav/viewpoint/CViewpointPlanner.h>

#include <nlohmann/json.hpp>

namespace risknav::viewpoint {
/** Writes plan.png, sweep.csv, sweep.md, strategies.csv and waypoints.ini
 * (an MRPT TWaypointSequence, [Waypoints], plus [Viewpoints] marking which
 * waypoints are viewpoints) into `out` (staged) and returns the summary
 * (without the app header). */
nlohmann::json writeViewpointReport(const CViewpointPlanner& p, common::COutputDir& out);

/** The optimal plan as MRPT waypoints: the path's vertices and its
 * viewpoints in order along it (viewpoints not skippable); isViewpoint[i]
 * tells which. */
struct TPlanWaypoints {
    std::vector<mrpt::math::TPoint2D> points;
    std::vector<int> viewpoint;  ///< index into the row's viewpoints, -1 for a vertex
};
TPlanWaypoints planWaypoints(const TPlanRow& row);

/** The risknav-viewpoint-plan app body. */
void runViewpointPlanApp(const common::TAppContext& ctx);

}  // namespace risknav::viewpoint
