#include <risknav/risk/CPosePropagator.h>
#include <risknav/risk/path_risk.h>

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

using mrpt::math::TPoint2D;

namespace risknav::risk {
double riskDensity(double dmax) {
    if (std::isinf(dmax))
        return 0.0;
    if (dmax <= 0)
        return std::numeric_limits<double>::infinity();
    return 1.0 / (dmax * dmax);
}

double integrateRisk(const std::vector<double>& s, const std::vector<double>& u) {
    double U = 0;
    for (size_t i = 1; i < s.size() && i < u.size(); i++)
        U += 0.5 * (u[i] + u[i - 1]) * (s[i] - s[i - 1]);
    return U;
}

void forEachMotionStep(const std::vector<TPoint2D>& path, const TOdometryModel& m,
                       double speed, double turnRate, double tau,
                       const std::function<void(const TMotionStep&)>& visit) {
    if (path.size() < 2)
        return;
    double x = path[0].x, y = path[0].y, s = 0;
    double theta = std::atan2(path[1].y - path[0].y, path[1].x - path[0].x);
    for (size_t i = 1; i < path.size(); i++) {
        const double dx = path[i].x - x, dy = path[i].y - y, len = std::hypot(dx, dy);
        if (len < 1e-9)
            continue;
        double turn = mrpt::math::wrapToPi(std::atan2(dy, dx) - theta);
        while (std::abs(turn) > 1e-9) {
            TMotionStep k;
            const double dth = std::clamp(turn, -turnRate * tau, turnRate * tau);
            k.theta = theta;
            k.tau = std::abs(dth) / turnRate;
            wheelsFromTwist(m, 0.0, dth / k.tau, k.uL, k.uR);
            k.x = x;
            k.y = y;
            k.s = s;
            k.turning = true;
            visit(k);
            theta = mrpt::math::wrapToPi(theta + dth);
            turn -= dth;
        }
        theta = std::atan2(dy, dx);
        const double ux = dx / len, uy = dy / len;
        double done = 0;
        while (done < len - 1e-12) {
            TMotionStep k;
            const double ds = std::min(speed * tau, len - done);
            k.theta = theta;
            k.tau = ds / speed;
            wheelsFromTwist(m, speed, 0.0, k.uL, k.uR);
            done += ds;
            s += ds;
            k.x = path[i - 1].x + ux * done;
            k.y = path[i - 1].y + uy * done;
            k.s = s;
            visit(k);
        }
        x = path[i].x;
        y = path[i].y;
    }
}

std::vector<TMotionStep> motionProfile(const std::vector<TPoint2D>& path,
                                       const TOdometryModel& m, double speed,
                                       double turnRate, double tau) {
    std::vector<TMotionStep> steps;
    forEachMotionStep(path, m, speed, turnRate, tau,
                      [&](const TMotionStep& k) { steps.push_back(k); });
    return steps;
}

TStepCount motionStepCount(const std::vector<TPoint2D>& path, double speed,
                           double turnRate, double tau) {
    TStepCount n;
    if (path.size() < 2)
        return n;
    double theta = std::atan2(path[1].y - path[0].y, path[1].x - path[0].x);
    for (size_t i = 1; i < path.size(); i++) {
        const double dx = path[i].x - path[i - 1].x, dy = path[i].y - path[i - 1].y,
                     len = std::hypot(dx, dy);
        if (len < 1e-9)
            continue;
        const double turn = std::abs(mrpt::math::wrapToPi(std::atan2(dy, dx) - theta));
        n.turning += std::ceil(turn / (turnRate * tau));
        n.straight += std::ceil(len / (speed * tau));
        theta = std::atan2(dy, dx);
    }
    return n;
}

TRiskResult evaluatePathRisk(const std::vector<TPoint2D>& path,
                             const std::vector<TSensingPoint>& sensing,
                             const CObstacleField& field, const TRiskOptions& opt) {
    TRiskResult res;
    if (path.size() < 2)
        return res;
    std::vector<bool> used(sensing.size(), false);
    double x = path[0].x, y = path[0].y, s = 0;
    double theta = std::atan2(path[1].y - path[0].y, path[1].x - path[0].x);
    CPosePropagator prop(opt.odometry, opt.model, opt.propagation, opt.sigmaP0, x, y,
                         theta, opt.samples, opt.seed);
    bool sensedSinceSample = false;

    auto checkSensing = [&]() {
        for (size_t i = 0; i < sensing.size(); i++)
            if (!used[i] &&
                std::hypot(sensing[i].x - x, sensing[i].y - y) <= sensing[i].radius) {
                used[i] = true;
                prop.reset(sensing[i].resetCov);
                res.sensed.push_back(sensing[i].name);
                sensedSinceSample = true;
            }
    };
    // Returns false (and sets the failure) when the covariance is not finite.
    auto sample = [&]() {
        TRiskSample k;
        k.s = s;
        k.x = x;
        k.y = y;
        k.theta = theta;
        k.bias = prop.bias();
        k.cov = prop.secondMoment();
        if (!k.cov.allFinite() || !k.bias.allFinite()) {
            char b[160];
            std::snprintf(b, sizeof(b),
                          "the covariance is not finite (an overflow) at s = %.2f m", s);
            res.failure = b;
            return false;
        }
        k.dmax = field.dMax(x, y, k.cov.block<2, 2>(0, 0));
        k.u = riskDensity(k.dmax.d);
        if (!(k.dmax.d == 0 || std::isfinite(k.u))) {  // D_max < 1e-154, or NaN
            char b[160];
            std::snprintf(b, sizeof(b),
                          "u = 1/D_max^2 overflows (D_max = %.3g) at s = %.2f m: the "
                          "covariance is too large",
                          k.dmax.d, s);
            res.failure = b;
            return false;
        }
        k.sensedHere = sensedSinceSample;
        sensedSinceSample = false;
        res.samples.push_back(k);
        return true;
    };

    checkSensing();
    bool ok = sample();
    double nextEval = opt.evalStep;
    if (ok)
        forEachMotionStep(path, opt.odometry, opt.speed, opt.turnRate, opt.tau,
                          [&](const TMotionStep& st) {
                              if (!ok)
                                  return;
                              double v, w;
                              twistFromWheels(opt.odometry, st.uL, st.uR, v, w);
                              theta = mrpt::math::wrapToPi(st.theta + w * st.tau);
                              x = st.x;
                              y = st.y;
                              s = st.s;
                              prop.step(st.theta, st.uL, st.uR, st.tau, x, y, theta);
                              if (st.turning)
                                  return;  // u is a density along the path length
                              checkSensing();
                              if (s >= nextEval - 1e-9 || sensedSinceSample) {
                                  ok = sample();
                                  while (nextEval <= s + 1e-9)
                                      nextEval += opt.evalStep;
                              }
                          });
    if (ok && res.samples.back().s < s - 1e-9)
        ok = sample();
    res.length = s;
    if (!ok) {
        res.U = res.uMax = std::numeric_limits<double>::infinity();
        res.sMaxU = s;
        return res;
    }

    std::vector<double> ss, uu;
    for (const auto& k : res.samples) {
        ss.push_back(k.s);
        uu.push_back(k.u);
        if (k.u > res.uMax) {
            res.uMax = k.u;
            res.sMaxU = k.s;
        }
        res.blocked |= k.dmax.d == 0;
    }
    res.U = integrateRisk(ss, uu);
    if (!std::isfinite(res.U) && !res.blocked) {  // every u finite, their sum not
        res.failure = "U = integral of u ds overflows: the covariance is too large";
        res.U = std::numeric_limits<double>::infinity();
    }
    return res;
}

bool routeWithSensingDetours(const std::vector<TPoint2D>& route,
                             const std::vector<TSensingPoint>& visit,
                             const CObstacleField& field, std::vector<TPoint2D>& out) {
    out.clear();
    struct TAttach {
        size_t seg;
        double t, arc;
        TPoint2D p;
        const TSensingPoint* sp;
    };
    std::vector<TAttach> att;
    for (const auto& sp : visit) {
        TAttach best{0, 0, 0, route[0], &sp};
        double bestD = std::numeric_limits<double>::infinity(), arc0 = 0;
        for (size_t i = 1; i < route.size(); i++) {
            const double ax = route[i - 1].x, ay = route[i - 1].y;
            const double vx = route[i].x - ax, vy = route[i].y - ay,
                         L2 = vx * vx + vy * vy;
            const double t =
                L2 > 0 ? std::clamp(((sp.x - ax) * vx + (sp.y - ay) * vy) / L2, 0.0, 1.0)
                       : 0.0;
            const TPoint2D p(ax + t * vx, ay + t * vy);
            const double d = std::hypot(sp.x - p.x, sp.y - p.y);
            if (d < bestD - 1e-12) {
                bestD = d;
                best = {i - 1, t, arc0 + t * std::sqrt(L2), p, &sp};
            }
            arc0 += std::sqrt(L2);
        }
        if (bestD > sp.radius && !field.segmentFree(best.p.x, best.p.y, sp.x, sp.y))
            return false;
        if (bestD > sp.radius)
            att.push_back(best);
    }
    std::sort(att.begin(), att.end(),
              [](const TAttach& a, const TAttach& b) { return a.arc < b.arc; });
    size_t k = 0;
    out.push_back(route[0]);
    for (size_t i = 1; i < route.size(); i++) {
        while (k < att.size() && att[k].seg == i - 1) {
            const auto& a = att[k++];
            if (std::hypot(a.p.x - out.back().x, a.p.y - out.back().y) > 1e-9)
                out.push_back(a.p);
            out.emplace_back(a.sp->x, a.sp->y);
            out.push_back(a.p);
        }
        if (std::hypot(route[i].x - out.back().x, route[i].y - out.back().y) > 1e-9)
            out.push_back(route[i]);
    }
    return true;
}

}  // namespace risknav::risk
