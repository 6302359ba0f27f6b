#pragma once
#include <limits>

namespace risknav::sim {
/** A disc obstacle (person, clutter) in world coordinates [m]. */
struct TDisc {
    double x = 0, y = 0, r = 0;
    int objectId = -1;  ///< stable id, for per-object sensor dropout
};

/** Distance from (ox, oy) along the unit direction (dx, dy) to the first
 * intersection with the disc's circle; +inf when the ray misses it or the
 * disc lies behind. An origin inside the disc returns 0 (the sensor is
 * covered). Solves |o + t d - c|^2 = r^2 for the smallest t >= 0. */
double rayDiscDistance(double ox, double oy, double dx, double dy, const TDisc& disc);

}  // namespace risknav::sim
