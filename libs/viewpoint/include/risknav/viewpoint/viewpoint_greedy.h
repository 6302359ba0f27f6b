#pragma once
#include <mrpt/math/TPoint2D.h>

#include <functional>
#include <vector>

/** Viewpoints along a path, greedily (Yamashita et al. 004 section IV-B,
 * eqs. (2)-(3); 003 section 5, eqs. (9)-(10)). Pure functions on a sampled
 * path. */
namespace risknav::viewpoint {
/** A point of the path: arc length, position, heading (the direction of
 * travel), and the error the robot may have there without touching an
 * obstacle: the clearance the path leaves, minus the robot radius (>= S on a
 * path planned with margin S; 003's A). */
struct TPathSample {
    double s = 0, x = 0, y = 0, heading = 0;
    double allowed = 0;  ///< [m]
};

/** Samples a polyline at most `step` apart, every vertex included; heading
 * of the segment that leaves the point (the last point: the one arriving);
 * allowed(p) gives the allowed error. */
std::vector<TPathSample> samplePath(
    const std::vector<mrpt::math::TPoint2D>& path, double step,
    const std::function<double(double x, double y)>& allowed);

/** m_max (eq. (2) / (9)): how far the robot may go from sample i after an
 * observation with position error ePos and heading error dPhi, while
 * D_max(m) + E_max(m) <= allowed along the way, with D_max(m) = dr * m (the
 * dead-reckoning error, a fraction of the distance) and E_max(m) = ePos +
 * 2 m sin(dPhi / 2) (eq. (1)). Between samples both sides are interpolated
 * linearly. Returns the distance to the path's end when the whole rest is
 * safe, and -1 when not even sample i is (ePos > allowed there). */
double reachFrom(const std::vector<TPathSample>& s, size_t i, double ePos, double dPhi,
                 double dr);

struct TGreedyResult {
    bool feasible = false;
    std::vector<size_t> viewpoints;  ///< sample indices, in order
    double reach = 0;  ///< [m] arc length reached (where the plan fails, when infeasible)
    size_t evaluations = 0;  ///< calls of bestReach
};

/** The greedy rule. From the start (known to ePos0, dPhi0), or the last
 * viewpoint p_s, the robot may reach m_s + m_max(p_s) (eq. (2)); among the
 * samples p_i up to there, the next viewpoint maximizes m_i + m_max(p_i)
 * (eq. (3)), m_max(p_i) with the best strategy at p_i (bestReach(i), < 0
 * when nothing can be observed there). Stops when the goal is reached;
 * infeasible when no candidate gets further than the current reach (there no
 * strategy keeps the error within the allowed error).
 *
 * The paper divides [p_s, p_g] into n + 1 positions; here every sample is a
 * candidate. With prune, candidates are visited in decreasing order of the
 * bound m_i + m_max(p_i; ePos = dPhi = 0) and the search stops when the bound
 * cannot beat the best found: the same choice as trying them all (prune =
 * false, kept for the tests), with a handful of strategy evaluations per
 * viewpoint instead of one per sample. Ties go to the farther candidate. */
TGreedyResult planViewpointsGreedy(const std::vector<TPathSample>& s, double ePos0,
                                   double dPhi0, double dr,
                                   const std::function<double(size_t i)>& bestReach,
                                   bool prune);

}  // namespace risknav::viewpoint
