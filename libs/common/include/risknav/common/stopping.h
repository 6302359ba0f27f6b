#pragma once
#include <algorithm>
#include <cmath>

namespace risknav::common {
/** Stopping distance of a robot moving at speed v [m/s]:
 *   d_stop(v) = t_delay * v + v^2 / (2 a)
 * Choi, Chung, Song (002), eqs. (1)-(3), with the PAPER_NOTES M3 erratum: the
 * paper prints d_brake = (1/2) alpha v^2; physics and its Table 1 say
 * v^2 / (2 a). t_delay [s] is the maximum detection + reaction delay,
 * a [m/s^2] the braking deceleration. With t_delay = 0.9 s, a = 1 m/s^2:
 * 0.8 -> 1.04 m, 0.5 -> 0.575 m, 0.2 -> 0.20 m (Table 1: 1.01, 0.58, 0.20). */
inline double stoppingDistance(double v, double tDelay, double decel) {
    v = std::max(0.0, v);
    return tDelay * v + v * v / (2.0 * decel);
}

/** The highest speed that stops within d [m]: the root v >= 0 of
 * d_stop(v) = d, v = a (sqrt(t_delay^2 + 2 d / a) - t_delay); 0 for d <= 0.
 * The inverse of stoppingDistance() (so stoppingDistance(v) <= d for every
 * v <= maxStoppableSpeed(d)). */
inline double maxStoppableSpeed(double d, double tDelay, double decel) {
    if (!(d > 0))
        return 0.0;
    return decel * (std::sqrt(tDelay * tDelay + 2.0 * d / decel) - tDelay);
}

}  // namespace risknav::common
