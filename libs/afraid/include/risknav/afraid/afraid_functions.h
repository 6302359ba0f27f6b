#pragma once
#include <mrpt/math/TPoint2D.h>

#include <cstddef>
#include <deque>
#include <vector>

namespace risknav::afraid {
// Sensed points are in the robot frame [m], x forward, y left, measured from
// the robot's centre, as mapping::scanToRobotFrame() gives them.

/** The collision-possible area of Choi, Chung, Song (002) Fig. 1 and section
 * 2.4 ("collision area and marginal area"): what the robot sweeps before it
 * can stop, plus the margin beta. ONE geometry for eqs. (5) and (8): the
 * rectangle ahead of the robot's centre, 0 < x <= radius + d_stop + beta,
 * |y| <= halfWidth (radius + lateral margin). The paper tests eq. 5 on the
 * distance to the obstacle and eq. 8 inside a circle; using one region for
 * both is what lets a person who enters from the side be seen by both
 * equations in the same frame (with a rectangle for one and a circle for the
 * other, the corner of the rectangle is reached first: obs_cur = 0 with
 * diff = 0, and the person is then "tracked" and never an event). */
struct TCollisionArea {
    double length = 0;     ///< [m] from the robot's centre: radius + d_stop + beta
    double halfWidth = 0;  ///< [m]
    bool contains(const mrpt::math::TPoint2D& p) const {
        return p.x > 0 && p.x <= length && p.y <= halfWidth && p.y >= -halfWidth;
    }
};

/** Eq. (5): obs_cur(t) = 0 when a sensed obstacle lies inside the collision
 * area (closer than d_stop + beta along the robot's way), else 1. */
int obsCur(const std::vector<mrpt::math::TPoint2D>& pts, const TCollisionArea& area);

/** Eq. (6): obs_predict(t) = product of obs_cur over the previous foot_step
 * cycles (history.back() is t-1). 1: nothing was in the collision area lately,
 * so an obstacle there now is not an already-tracked, expected one. With less
 * history than foot_step, only what there is counts. */
int obsPredict(const std::deque<int>& history, size_t footStep);

/** Eqs. (8)-(9): the non-blocked area, the sum over nDirections directions
 * theta of the forward half-plane [-90, +90] deg of the reach distance: how
 * far the robot's swept corridor (half-width area.halfWidth) along theta is
 * free, capped at area.length. An obstacle point (distance d, bearing theta')
 * blocks direction theta when its lateral offset d |sin(theta - theta')| <=
 * halfWidth, and the reach is then its distance along theta,
 * d cos(theta - theta'). Erratum (beyond the paper): eq. (8) prints
 * d sin(|dtheta|), the LATERAL offset, as the reach of a blocked direction;
 * that is not a length along the direction and shrinks as the obstacle comes
 * straight ahead, so the along-track distance (cos) is used, which is what
 * the blocked/non-blocked areas of Figs. 4-5 measure. Only points inside the
 * collision area block (the same region as eq. 5). */
double nonBlockedArea(const std::vector<mrpt::math::TPoint2D>& pts,
                      const TCollisionArea& area, int nDirections = 181);

/** Eq. (10), normalised: |E_area - A_area| as a fraction of the whole
 * collision-possible area (nDirections * area.length), so that one threshold
 * means the same at every speed and direction count (the paper's threshold is
 * in summed metres, which grow with d_stop). In [0, 1]. */
double areaDifference(double expectedArea, double actualArea, const TCollisionArea& area,
                      int nDirections = 181);

/** Eq. (11), written out: Afr(t) = 1 when an obstacle is in the collision area
 * now (obs_cur = 0) that was not there during the previous foot_step cycles
 * (obs_predict = 1) and the non-blocked area differs from what the map
 * predicts at the localized pose by more than the threshold (diff > thr: the
 * obstacle is not a mapped wall). The paper prints "Afr = obs_cur if diff >
 * thr"; with obs_cur = 1 meaning "clear" that would flag clear scenes, so the
 * intent (PAPER_NOTES M3) is implemented: unexpected AND new AND inside. */
bool afraidFlag(int obsCurNow, int obsPredictNow, double diff, double diffThreshold);

}  // namespace risknav::afraid
