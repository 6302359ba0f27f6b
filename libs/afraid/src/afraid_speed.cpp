#include <risknav/afraid/afraid_speed.h>

#include <algorithm>
#include <cmath>

using mrpt::math::TPoint2D;

namespace risknav::afraid {
int TRouteAxis::binOf(double x, double y) const {
    return std::clamp(int(std::floor((along(x, y) - lo) / bin)), 0, int(pos.size()) - 1);
}

TRouteAxis routeAxis(const std::vector<TPoint2D>& t, double bin) {
    TRouteAxis a;
    a.bin = bin;
    for (const auto& p : t) {
        a.mx += p.x / t.size();
        a.my += p.y / t.size();
    }
    double sxx = 0, syy = 0, sxy = 0;
    for (const auto& p : t) {
        sxx += (p.x - a.mx) * (p.x - a.mx);
        syy += (p.y - a.my) * (p.y - a.my);
        sxy += (p.x - a.mx) * (p.y - a.my);
    }
    const double ang = 0.5 * std::atan2(2 * sxy, sxx - syy);
    a.ux = std::cos(ang);
    a.uy = std::sin(ang);
    if (a.ux < 0 || (a.ux == 0 && a.uy < 0)) {
        a.ux = -a.ux;
        a.uy = -a.uy;
    }
    double lo = 1e18, hi = -1e18;
    for (const auto& p : t) {
        const double s = a.along(p.x, p.y);
        lo = std::min(lo, s);
        hi = std::max(hi, s);
    }
    a.lo = lo;
    const int nb = std::max(1, int(std::ceil((hi - lo) / bin)) + 1);
    const double o = a.offset();
    a.pos.resize(size_t(nb));
    for (int b = 0; b < nb; b++)
        a.pos[size_t(b)] = (lo + (b + 0.5) * bin) + o;
    return a;
}

std::pair<double, double> zoneSpan(const TAfraidZone& z, const TRouteAxis& a) {
    const double p = z.xMin * a.ux + z.yMin * a.uy, q = z.xMax * a.ux + z.yMax * a.uy;
    return {std::min(p, q), std::max(p, q)};
}

std::vector<double> speedAlongAxis(const std::function<double(double, double)>& level,
                                   const TRouteAxis& a, const TAfraidSpeedParams& p) {
    const double o = a.offset();
    std::vector<double> vs(a.pos.size());
    for (size_t i = 0; i < a.pos.size(); i++) {
        const double s0 = a.pos[i] - o;
        const TPoint2D p0(a.mx + s0 * a.ux, a.my + s0 * a.uy),
            p1(a.mx + (s0 + p.lookAhead) * a.ux, a.my + (s0 + p.lookAhead) * a.uy);
        vs[i] = afraidSpeedLimit(level, {p0, p1}, p.vMax, p.vMax, p.vSafe, p.threshold,
                                 p.tDelay, p.decel);
    }
    return vs;
}

std::optional<TTenMetreComparison> compareSection(const TRouteAxis& a,
                                                  const std::vector<double>& speed,
                                                  const std::vector<TAfraidZone>& zones,
                                                  double vBefore, double length,
                                                  double leadIn) {
    const auto& pos = a.pos;
    if (zones.empty() || pos.size() < 2)
        return std::nullopt;
    double firstZone = 1e18;
    for (const auto& z : zones)
        firstZone = std::min(firstZone, zoneSpan(z, a).first);
    const double s0 = std::max(pos.front(), firstZone - leadIn), s1 = s0 + length;
    double tAfter = 0;
    for (size_t i = 1; i < pos.size(); i++)
        if (pos[i] > s0 && pos[i] <= s1)
            tAfter += (pos[i] - pos[i - 1]) / speed[i];
    const double span = std::min(s1, pos.back()) - s0;
    TTenMetreComparison c;
    c.fromM = s0;
    c.toM = s0 + span;
    c.lengthM = span;
    c.timeBeforeS = span / vBefore;
    c.timeAfterS = tAfter;
    c.meanSpeedAfter = tAfter > 0 ? span / tAfter : 0.0;
    return c;
}

std::optional<TRouteSpeedProfile> routeSpeedProfile(
    const std::function<double(double, double)>& level,
    const std::vector<TPoint2D>& trajectory, const std::vector<TAfraidZone>& zones,
    const TAfraidSpeedParams& p) {
    if (trajectory.size() <= 2)
        return std::nullopt;
    TRouteSpeedProfile r;
    r.axis = routeAxis(trajectory);
    r.speed = speedAlongAxis(level, r.axis, p);
    r.tenMetre = compareSection(r.axis, r.speed, zones, p.vSafe);
    return r;
}

}  // namespace risknav::afraid
