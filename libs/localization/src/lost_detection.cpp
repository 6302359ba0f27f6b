#include <risknav/common/config_read.h>
#include <risknav/localization/lost_detection.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::localization {
void TLostDetectionOptions::declare(Visitor& v) {
    // the *_deg keys are held in degrees (they are compared, not turned by)
    v.number(fit_distance, "fit_distance", TRange{0, 10, true, false, "m"},
             "a scan point within this of a map obstacle fits the map");
    v.number(min_fit, "min_fit", TRange::closed(0, 1),
             "fraction of the scan's points that must fit at the mean pose");
    v.number(max_range, "max_range", TRange::closed(0, 1000, "m"),
             "returns farther than this are not counted (0 = every range)");
    v.integer(min_points, "min_points", TRange::closed(1, 100000),
              "fewer points within max_range and the fit is not judged");
    v.number(max_spread_xy, "max_spread_xy", TRange{0, 1e6, true, false, "m"},
             "particles' position spread above which the filter has no estimate");
    v.number(max_spread_phi_deg, "max_spread_phi_deg", TRange{0, 360, true, false, "deg"},
             "the same for the heading's standard deviation");
    v.integer(lost_after, "lost_after", TRange::closed(1, 100000),
              "consecutive failed checks that make the filter lost");
    v.integer(converge_checks, "converge_checks", TRange::closed(1, 100000),
              "checks a new or re-spread filter may take to converge");
    v.number(recovery_xy, "recovery_xy", TRange{0, 1e6, true, false, "m"},
             "recover(): half-width of the box the particles are re-spread over");
    v.number(recovery_phi_deg, "recovery_phi_deg", TRange::closed(0, 180, "deg"),
             "recover(): heading half-range");
    v.integer(recovery_particles, "recovery_particles", TRange::closed(10, 1000000),
              "recover(): particles drawn");
}

TLocalizationCheck judgeLocalization(const TScanFit& fit, double spreadXY,
                                     double spreadPhiDeg,
                                     const TLostDetectionOptions& o) {
    TLocalizationCheck c;
    c.fit = fit;
    c.fitFraction = fit.fraction();
    c.fitJudged = fit.points >= size_t(o.min_points);
    c.spreadXY = spreadXY;
    c.spreadPhiDeg = spreadPhiDeg;
    if (c.fitJudged && !(c.fitFraction >= o.min_fit))
        c.reason = "scan_fit";
    else if (!(spreadXY <= o.max_spread_xy))
        c.reason = "spread_xy";
    else if (!(spreadPhiDeg <= o.max_spread_phi_deg))
        c.reason = "spread_phi";
    c.failed = !c.reason.empty();
    c.lost = c.failed;
    c.consecutiveFailed = c.failed ? 1 : 0;
    return c;
}
}  // namespace risknav::localization
