#include <risknav/common/config_read.h>
#include <risknav/localization/lost_detection.h>

#include <cmath>

using namespace risknav::common;

namespace risknav::localization {
void TLostDetectionOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                               const std::string& s) {
    section = s;
    fit_distance = readDouble(c, s, "fit_distance", fit_distance);
    min_fit = readDouble(c, s, "min_fit", min_fit);
    max_range = readDouble(c, s, "max_range", max_range);
    min_points = readInt(c, s, "min_points", min_points);
    max_spread_xy = readDouble(c, s, "max_spread_xy", max_spread_xy);
    max_spread_phi_deg = readDouble(c, s, "max_spread_phi_deg", max_spread_phi_deg);
    lost_after = readInt(c, s, "lost_after", lost_after);
    converge_checks = readInt(c, s, "converge_checks", converge_checks);
    recovery_xy = readDouble(c, s, "recovery_xy", recovery_xy);
    recovery_phi_deg = readDouble(c, s, "recovery_phi_deg", recovery_phi_deg);
    recovery_particles = readInt(c, s, "recovery_particles", recovery_particles);
}

void TLostDetectionOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                             const std::string& s) const {
    writeKey(c, s, "fit_distance", fit_distance);
    writeKey(c, s, "min_fit", min_fit);
    writeKey(c, s, "max_range", max_range);
    writeKey(c, s, "min_points", min_points);
    writeKey(c, s, "max_spread_xy", max_spread_xy);
    writeKey(c, s, "max_spread_phi_deg", max_spread_phi_deg);
    writeKey(c, s, "lost_after", lost_after);
    writeKey(c, s, "converge_checks", converge_checks);
    writeKey(c, s, "recovery_xy", recovery_xy);
    writeKey(c, s, "recovery_phi_deg", recovery_phi_deg);
    writeKey(c, s, "recovery_particles", recovery_particles);
}

void TLostDetectionOptions::validate() const {
    const std::string& s = section;
    checkKey(s, "fit_distance", fit_distance, TRange{0, 10, true, false, "m"});
    checkKey(s, "min_fit", min_fit, TRange::closed(0, 1));
    checkKey(s, "max_range", max_range, TRange::closed(0, 1000, "m"));
    checkKey(s, "min_points", double(min_points), TRange::closed(1, 100000));
    checkKey(s, "max_spread_xy", max_spread_xy, TRange{0, 1e6, true, false, "m"});
    checkKey(s, "max_spread_phi_deg", max_spread_phi_deg,
             TRange{0, 360, true, false, "deg"});
    checkKey(s, "lost_after", double(lost_after), TRange::closed(1, 100000));
    checkKey(s, "converge_checks", double(converge_checks), TRange::closed(1, 100000));
    checkKey(s, "recovery_xy", recovery_xy, TRange{0, 1e6, true, false, "m"});
    checkKey(s, "recovery_phi_deg", recovery_phi_deg, TRange::closed(0, 180, "deg"));
    checkKey(s, "recovery_particles", double(recovery_particles),
             TRange::closed(10, 1000000));
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
