#pragma once
#include <cstddef>
#include <vector>

namespace risknav::speed {
/** The narrow-space rule of Miura et al. (000) section 4.1, with the
 * cost-to-go reading of PAPER_NOTES M1:
 *
 *   Sort the candidate speeds by cost-to-go (path length + straight-line
 *   distance left from the path's end to the destination). A jump larger than
 *   `threshold` between consecutive values means a narrow passage that the
 *   speeds after the jump cannot use (with a complete planner they detour or
 *   stop short; either way their cost-to-go is larger). Split the list at
 *   the first such jump: the group with the smaller cost-to-go is safe. No
 *   jump: every speed is safe.
 *
 * (The paper keeps "the longer group" because its planner stops short of a
 * passage it cannot pass, giving the failing speed a SHORTER path; measuring
 * cost-to-go covers both planners with one rule.)
 * Returns the indices of the safe speeds, in the input's order. Infinite
 * costs (no path at all) are never safe unless every cost is infinite. */
std::vector<size_t> safeSpeedsByGap(const std::vector<double>& costToGo,
                                    double threshold);

/** The undecided-region rule of (000) section 3.1 (its display inequality): a speed v is
 * safe iff d / (v T) >= N, d the along-path distance to the first undecided
 * region, T the cycle time, N the necessary number of observations. */
bool undecidedRuleHolds(double d, double v, double cycleTime, int necessaryObservations);
}  // namespace risknav::speed
