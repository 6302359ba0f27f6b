#pragma once
#include <mrpt/math/TPoint2D.h>

#include <functional>
#include <vector>

namespace risknav::afraid {
class CAfraidGrid;

/** A connected region of the map where the learned afraid level is above
 * the threshold. */
struct TAfraidZone {
    int id = 0;
    double xMin = 0, xMax = 0, yMin = 0, yMax = 0;  ///< bounding box [m]
    double area = 0;                                ///< [m^2]
    double peak = 0;                                ///< highest level inside
    int cells = 0;
    unsigned robotEvents = 0, obstacleEvents = 0;
    std::vector<int> mask;  ///< cell indices (row-major)
    /** Where the robot must already be slow for this zone: its cells grown by
     * the approach distance (may overlap another zone's). Bounding box [m]. */
    double slowXMin = 0, slowXMax = 0, slowYMin = 0, slowYMax = 0;
    std::vector<int> slowMask;  ///< cell indices (row-major)
};

/** Zones = 8-connected regions with level > threshold (OpenCV connected
 * components), each with where the robot must already be slow for it: the
 * zone grown by `approach` [m] (the stopping distance at the fast speed plus
 * the robot's radius: a robot coming from any side has to brake there). */
std::vector<TAfraidZone> findZones(const std::vector<float>& level, const CAfraidGrid& g,
                                   double threshold, double approach = 0);

/** Choi, Chung, Song (002) eqs. (13)-(14), with a look-ahead: v_afraid =
 * v_safe when the level exceeds the threshold anywhere on the path ahead within
 * the stopping distance at v_max (d_stop = t_delay v + v^2/(2a)), else v_max;
 * the command is min(v_behaviour, v_afraid). The paper tests only the
 * robot's own cell, so the robot would still be fast when it enters a zone;
 * looking ahead over d_stop(v_max) makes it slow on arrival (beyond the paper,
 * as PAPER_NOTES M3 asks). `pathAhead` starts at the robot. */
double afraidSpeedLimit(const std::function<double(double, double)>& level,
                        const std::vector<mrpt::math::TPoint2D>& pathAhead,
                        double vBehaviour, double vMax, double vSafe, double threshold,
                        double tDelay, double decel, double step = 0.05);

}  // namespace risknav::afraid
