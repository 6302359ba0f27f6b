#pragma once
#include <risknav/mapping/CDistanceField.h>

#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cstddef>
#include <limits>
#include <string>

namespace risknav::localization {
/** How a scan fits a map at a pose. */
struct TScanFit {
    size_t points = 0;   ///< valid returns (within maxRange)
    size_t onMap = 0;    ///< of them, on the map's cells
    size_t fitting = 0;  ///< of those, on the surface of a map obstacle
    /** fitting / points (a point off the map is no evidence for the pose, so
     * it does not fit); NaN without points. */
    double fraction() const {
        return points ? double(fitting) / double(points)
                      : std::numeric_limits<double>::quiet_NaN();
    }
};

/** The scan-to-map fit at `pose` (the robot's, world frame): each valid
 * return (mapping::scanToRobotFrame(), the sensor's pose on the robot
 * applied) no farther than maxRange [m] from the sensor is placed in the
 * world and fits when it lies on the surface of a map obstacle: within
 * fitDistance [m] of one from outside (CDistanceField::clearance) and not
 * deeper than fitDistance inside one (CDistanceField::depth: a point deep
 * in a solid wall is as wrong as one in the open). A point off the map
 * counts, and does not fit. A pure function: shared by the afraid learner's
 * "localized" test and CRawlogMcl's lost-localization test. */
TScanFit scanMapFit(const mapping::CDistanceField& field,
                    const mrpt::obs::CObservation2DRangeScan& scan,
                    const mrpt::math::TPose2D& pose, double fitDistance,
                    double maxRange = std::numeric_limits<double>::infinity());

/** The frame's first 2D range scan, or its first one labelled `label` ("" =
 * any label); nullptr when it holds none. */
mrpt::obs::CObservation2DRangeScan::Ptr firstRangeScan(const mrpt::obs::CSensoryFrame& sf,
                                                       const std::string& label = "");
}  // namespace risknav::localization
