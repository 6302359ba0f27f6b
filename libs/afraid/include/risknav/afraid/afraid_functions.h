#pragma once
#include <mrpt/math/TPoint2D.h>

#include <cstddef>
#include <deque>
#include <vector>

namespace risknav::afraid {
// Sensed points are in the robot frame [m], x forward, y left, as
// mapping::scanToRobotFrame() gives them.

/** Choi, Chung, Song (002) eq. (5): obs_cur(t) = 1 when every sensed obstacle
 * is at least dist_stop + beta away, 0 when one is closer. "Obstacles" are the
 * points in the collision area of Fig. 1: ahead of the robot (x > 0) and inside
 * its swept corridor (|y| <= halfWidth); distance along the path (x). */
int obsCur(const std::vector<mrpt::math::TPoint2D>& pts, double dStop, double beta,
           double halfWidth);

/** Eq. (6): obs_predict(t) = product of obs_cur over the previous foot_step
 * cycles (history.back() is t-1). 1: nothing was in the collision area lately,
 * so an obstacle there now is not an already-tracked, expected one. With less
 * history than foot_step, only what there is counts. */
int obsPredict(const std::deque<int>& history, size_t footStep);

/** Eqs. (8)-(9): the non-blocked area, the sum over directions theta in the
 * forward half-plane [-90, +90] deg (nDirections of them) of the reach
 * distance. Eq. (8) as printed: an obstacle at distance d and bearing theta'
 * blocks direction theta when its lateral offset d |sin(theta - theta')| <= r
 * (the robot's half-width), and the reach is then that lateral offset; an
 * unblocked direction reaches dist_stop. Only obstacles that the robot could
 * meet, in front (cos(theta - theta') > 0) and within dist_stop + beta, block.
 * (The paper's eq. 8 takes the min over all obstacles; far walls would block
 * every direction, which the collision-area reading of Figs. 4-5 excludes.) */
double nonBlockedArea(const std::vector<mrpt::math::TPoint2D>& pts, double dStop,
                      double beta, double r, int nDirections = 181);

/** Eq. (11), written out: Afr(t) = 1 when an obstacle is in the collision area
 * now (obs_cur = 0) that was not there during the previous foot_step cycles
 * (obs_predict = 1) and the non-blocked area differs from what the map
 * predicts at the localized pose by more than the threshold (diff > thr: the
 * obstacle is not a mapped wall). The paper prints "Afr = obs_cur if diff >
 * thr"; with obs_cur = 1 meaning "clear" that would flag clear scenes, so the
 * intent (PAPER_NOTES M3) is implemented: unexpected AND new AND inside. */
bool afraidFlag(int obsCurNow, int obsPredictNow, double diff, double diffThreshold);

}  // namespace risknav::afraid
