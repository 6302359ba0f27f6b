#pragma once
#include <cmath>

namespace risknav::mapping {
/** The bound [rad] on |fastAtan2(y, x) - std::atan2(y, x)| that callers rely
 * on (the polynomial's own error is 1.4e-8; a test checks < half of this on
 * a dense sweep). */
constexpr double kFastAtan2MaxError = 1e-7;

/** atan2 from the polynomial of Abramowitz & Stegun 4.4.49 on [0, 1] (error
 * <= 2e-8) and the octant symmetries: a few multiplications instead of a
 * libm call. Only for a first guess that is confirmed where it matters:
 * CLocalProbGrid::integrateScan falls back to std::atan2 near a ray
 * boundary. (0, 0) gives 0. */
inline double fastAtan2(double y, double x) {
    const double ax = std::fabs(x), ay = std::fabs(y);
    if (ax == 0 && ay == 0)
        return 0.0;
    const bool steep = ay > ax;
    const double z = steep ? ax / ay : ay / ax;
    const double z2 = z * z;
    double a =
        z * (1.0 + z2 * (-0.3333314528 +
                         z2 * (0.1999355085 +
                               z2 * (-0.1420889944 +
                                     z2 * (0.1065626393 +
                                           z2 * (-0.0752896400 +
                                                 z2 * (0.0429096138 +
                                                       z2 * (-0.0161657367 +
                                                             z2 * 0.0028662257))))))));
    if (steep)
        a = M_PI_2 - a;
    if (x < 0)
        a = M_PI - a;
    return y < 0 ? -a : a;
}
}  // namespace risknav::mapping
