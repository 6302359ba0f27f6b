#pragma once
#include <risknav/afraid/afraid_zones.h>

#include <mrpt/math/TPoint2D.h>

#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace risknav::afraid {
/** The route's main axis: the principal axis of the trajectory, the "along
 * the corridor" axis of Choi, Chung, Song (002) Figs. 8-9 (exact for a
 * corridor, an approximation for other routes), cut in bins that cover the
 * trajectory's projection. Positions "world-projected" are world points
 * projected on the axis direction (x u_x + y u_y): for a corridor along x,
 * x itself, so door positions compare directly. */
struct TRouteAxis {
    double mx = 0, my = 0;    ///< the trajectory's mean [m]
    double ux = 1, uy = 0;    ///< unit direction: u_x > 0, or u_x = 0 and u_y > 0
    double lo = 0;            ///< lowest along() of the trajectory [m]
    double bin = 0.1;         ///< bin width [m]
    std::vector<double> pos;  ///< bin centres, world-projected [m]

    /** Signed distance of (x, y) from the mean along the axis [m]. */
    double along(double x, double y) const { return (x - mx) * ux + (y - my) * uy; }
    /** World-projected position = along() + offset(). */
    double offset() const { return mx * ux + my * uy; }
    /** The bin of (x, y), clamped to the first and last bin. */
    int binOf(double x, double y) const;
};

/** The axis of a trajectory of at least one point: mean, direction
 * a = atan2(2 s_xy, s_xx - s_yy) / 2 of the covariance's principal axis, and
 * ceil((max - min) / bin) + 1 bins from the lowest projection. */
TRouteAxis routeAxis(const std::vector<mrpt::math::TPoint2D>& trajectory,
                     double bin = 0.1);

/** The world-projected extent [from, to] of a zone's bounding box on the axis. */
std::pair<double, double> zoneSpan(const TAfraidZone& z, const TRouteAxis& a);

/** What afraidSpeedLimit() needs besides the level (Choi, Chung, Song (002)
 * eqs. 13-14 and the stopping distance of eqs. 1-3). */
struct TAfraidSpeedParams {
    double vMax = 0.8, vSafe = 0.2;  ///< [m/s]
    double threshold = 0.04;         ///< level above which v_afraid = v_safe
    double tDelay = 0.9;             ///< [s]
    double decel = 1.0;              ///< [m/s^2]
    double lookAhead = 5.0;          ///< [m] path ahead given to the limit
};

/** The speed limit v = min(v_behaviour, v_afraid) (eqs. 13-14 with the
 * look-ahead of afraidSpeedLimit(), v_behaviour = v_max) at every position of
 * a.pos, driving towards +axis along the axis line. */
std::vector<double> speedAlongAxis(const std::function<double(double, double)>& level,
                                   const TRouteAxis& a, const TAfraidSpeedParams& p);

/** The paper's 10 m comparison (Choi, Chung, Song (002) section 3: a 10 m
 * section took 51.3 s before learning and 24.3 s after). */
struct TTenMetreComparison {
    double fromM = 0, toM = 0;  ///< the section, world-projected [m]
    double lengthM = 0;         ///< its length, s1 - s0 [m]
    double timeBeforeS = 0;     ///< at v_before everywhere (before learning)
    double timeAfterS = 0;      ///< with the learned speed limit
    double meanSpeedAfter = 0;  ///< (toM - fromM) / timeAfterS [m/s], 0 if no time
};

/** The section starts `leadIn` m before the first zone on the axis (not
 * before the route's first position) and is `length` m long, cut at the
 * route's last position: s0 = max(pos_0, z_first - leadIn),
 * s1 = min(s0 + length, pos_last). Before learning the robot drives at
 * vBefore (the learning speed v_safe): t_before = (s1 - s0) / vBefore. After:
 * t_after = sum over positions i >= 1 with s0 < pos_i <= s0 + length of
 * (pos_i - pos_{i-1}) / speed_i. nullopt without a zone or with fewer than
 * two positions. `speed` is per a.pos (speedAlongAxis()). */
std::optional<TTenMetreComparison> compareSection(const TRouteAxis& a,
                                                  const std::vector<double>& speed,
                                                  const std::vector<TAfraidZone>& zones,
                                                  double vBefore, double length = 10.0,
                                                  double leadIn = 1.0);

/** Axis, speed limit along it and the 10 m comparison of a learned level. */
struct TRouteSpeedProfile {
    TRouteAxis axis;
    std::vector<double> speed;  ///< per axis.pos [m/s]
    std::optional<TTenMetreComparison> tenMetre;
};

/** routeAxis() + speedAlongAxis() + compareSection() with v_before = v_safe;
 * nullopt for a trajectory of fewer than three points. */
std::optional<TRouteSpeedProfile> routeSpeedProfile(
    const std::function<double(double, double)>& level,
    const std::vector<mrpt::math::TPoint2D>& trajectory,
    const std::vector<TAfraidZone>& zones, const TAfraidSpeedParams& p);

}  // namespace risknav::afraid
