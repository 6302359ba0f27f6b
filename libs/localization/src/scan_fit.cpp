#include <risknav/localization/scan_fit.h>
#include <risknav/mapping/scan_points.h>

#include <mrpt/poses/CPose2D.h>

#include <cmath>

namespace risknav::localization {
TScanFit scanMapFit(const mapping::CDistanceField& field,
                    const mrpt::obs::CObservation2DRangeScan& scan,
                    const mrpt::math::TPose2D& pose, double fitDistance,
                    double maxRange) {
    TScanFit f;
    const mrpt::poses::CPose2D robot(pose);
    const double sx = scan.sensorPose.x(), sy = scan.sensorPose.y();
    for (const auto& p : mapping::scanToRobotFrame(scan)) {
        if (std::hypot(p.x - sx, p.y - sy) > maxRange)
            continue;
        f.points++;
        const auto w = robot + mrpt::poses::CPose2D(p.x, p.y, 0);
        const int cx = field.x2idx(w.x()), cy = field.y2idx(w.y());
        if (!field.inside(cx, cy))
            continue;  // no evidence for the pose: counted, not fitting
        f.onMap++;
        if (field.clearance(cx, cy) <= fitDistance && field.depth(cx, cy) <= fitDistance)
            f.fitting++;
    }
    return f;
}

mrpt::obs::CObservation2DRangeScan::Ptr firstRangeScan(const mrpt::obs::CSensoryFrame& sf,
                                                       const std::string& label) {
    for (const auto& o : sf) {
        auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(o);
        if (s && (label.empty() || s->sensorLabel == label))
            return s;
    }
    return {};
}
}  // namespace risknav::localization
