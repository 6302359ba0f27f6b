#include <risknav/viewpoint/observation_model.h>

#include <mrpt/math/wrap2pi.h>

#include <cmath>

using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;

namespace risknav::viewpoint {
namespace {
int camIndex(int side) {
    return side > 0 ? 0 : 1;
}
double cross(const TPoint2D& a, const TPoint2D& b) {
    return a.x * b.y - a.y * b.x;
}
double wrap(double a) {
    return mrpt::math::wrapToPi(a);
}

// Camera centre in the robot frame.
TPoint2D camLocal(int side, double b_r) {
    return {0, side * b_r};
}

// Bearing (robot frame) of the ray through image column u of a camera panned by pan.
TPoint2D rayDir(double pan, double u, double f) {
    const double a = pan - std::atan(u / f);
    return {std::cos(a), std::sin(a)};
}

// The pose that maps the robot-frame points q1, q2 onto the world points w1, w2
// (the rotation from the two directions, the translation from the midpoints).
TPose2D alignTwoPoints(const TPoint2D& q1, const TPoint2D& q2, const TPoint2D& w1,
                       const TPoint2D& w2) {
    const double phi =
        wrap(std::atan2(w2.y - w1.y, w2.x - w1.x) - std::atan2(q2.y - q1.y, q2.x - q1.x));
    const double c = std::cos(phi), s = std::sin(phi);
    const TPoint2D qm{(q1.x + q2.x) / 2, (q1.y + q2.y) / 2};
    const TPoint2D wm{(w1.x + w2.x) / 2, (w1.y + w2.y) / 2};
    return {wm.x - (c * qm.x - s * qm.y), wm.y - (s * qm.x + c * qm.y), phi};
}

std::optional<TPoint2D> intersectRays(const TPoint2D& c1, const TPoint2D& d1,
                                      const TPoint2D& c2, const TPoint2D& d2) {
    const double det = -cross(d1, d2);
    if (std::abs(det) < 1e-12)
        return std::nullopt;
    const TPoint2D w{c2.x - c1.x, c2.y - c1.y};
    const double lam = cross(w, {-d2.x, -d2.y}) / det;
    const double mu = cross(d1, w) / det;
    if (!(lam > 0 && mu > 0))
        return std::nullopt;
    return TPoint2D{c1.x + lam * d1.x, c1.y + lam * d1.y};
}

std::optional<TPose2D> solveStereo(const TObservation& o, const TMeasurement& z,
                                   const std::vector<TLandmark>& lms,
                                   const TCameraRig& rig) {
    const auto [wp, wm] = landmarkEnds(lms[size_t(o.lm[0])]);
    const TPoint2D cL = camLocal(+1, rig.b_r), cR = camLocal(-1, rig.b_r);
    auto end = [&](double sgn) {
        return intersectRays(cL, rayDir(o.pan[0], z[0] + sgn * z[1], rig.focal), cR,
                             rayDir(o.pan[1], z[2] + sgn * z[3], rig.focal));
    };
    const auto qp = end(+1), qm = end(-1);
    if (!qp || !qm)
        return std::nullopt;
    return alignTwoPoints(*qp, *qm, wp, wm);
}

std::optional<TPose2D> solveTwoLandmark(const TObservation& o, const TMeasurement& z,
                                        const std::vector<TLandmark>& lms,
                                        const TCameraRig& rig, const TPose2D& prior) {
    const TLandmark& lj = lms[size_t(o.lm[0])];
    const TLandmark& li = lms[size_t(o.lm[1])];
    if (!(z[1] > 0))
        return std::nullopt;
    // Near landmark j: distance from its apparent size, l = f r / r_image
    // (the depth along the axis; the lateral offset from u).
    const double panN = o.pan[size_t(camIndex(o.side))];
    const double panF = o.pan[size_t(camIndex(-o.side))];
    const TPoint2D cn = camLocal(o.side, rig.b_r), cf = camLocal(-o.side, rig.b_r);
    const double t = rig.focal * lj.radius / z[1];
    const double s = t * z[0] / rig.focal;
    const TPoint2D qj{cn.x + t * std::cos(panN) + s * std::sin(panN),
                      cn.y + t * std::sin(panN) - s * std::cos(panN)};
    // Far landmark i on the ray from the other camera at distance d_ij from j.
    const TPoint2D e = rayDir(panF, z[2], rig.focal);
    const double dij = std::hypot(li.x - lj.x, li.y - lj.y);
    const TPoint2D w{cf.x - qj.x, cf.y - qj.y};
    const double b = e.x * w.x + e.y * w.y;
    const double disc = b * b - (w.x * w.x + w.y * w.y - dij * dij);
    if (disc < 0)
        return std::nullopt;
    std::optional<TPose2D> best;
    double bestD = 0;
    for (const double sgn : {-1.0, 1.0}) {
        const double lam = -b + sgn * std::sqrt(disc);
        if (!(lam > 1e-9))
            continue;
        const TPoint2D qi{cf.x + lam * e.x, cf.y + lam * e.y};
        const TPose2D p = alignTwoPoints(qj, qi, {lj.x, lj.y}, {li.x, li.y});
        const double d = std::hypot(p.x - prior.x, p.y - prior.y);
        if (!best || d < bestD) {
            best = p;
            bestD = d;
        }
    }
    return best;
}

// The three bearing equations, prepared once per solve: landmark position,
// camera offset and the measured bearing relative to the robot's heading.
struct TBearings {
    double lx[3], ly[3], sb[3], meas[3];
    TBearings(const TObservation& o, const TMeasurement& z,
              const std::vector<TLandmark>& lms, const TCameraRig& rig) {
        for (int k = 0; k < 3; k++) {
            const int side = k < 2 ? o.side : -o.side;
            const TLandmark& l = lms[size_t(o.lm[size_t(k)])];
            lx[k] = l.x;
            ly[k] = l.y;
            sb[k] = side * rig.b_r;
            meas[k] = o.pan[size_t(camIndex(side))] - std::atan(z[size_t(k)] / rig.focal);
        }
    }
    // Residuals r_k = bearing(L_k from camera k) - (phi + measured), and
    // their Jacobian w.r.t. (x, y, phi) when J is given.
    void eval(const TPose2D& p, double r[3], double (*J)[3]) const {
        const double s = std::sin(p.phi), c = std::cos(p.phi);
        for (int k = 0; k < 3; k++) {
            const double dx = lx[k] - (p.x - sb[k] * s), dy = ly[k] - (p.y + sb[k] * c);
            r[k] = wrap(std::atan2(dy, dx) - (p.phi + meas[k]));
            if (J) {
                const double q = dx * dx + dy * dy;
                J[k][0] = dy / q;
                J[k][1] = -dx / q;
                J[k][2] = (-dy * sb[k] * c + dx * sb[k] * s) / q - 1;
            }
        }
    }
};

double det3(const double J[3][3]) {
    return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
           J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
           J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

// Closed-form resection with both cameras taken at the robot centre: the
// robot sees L0L1 under the angle t01 and L1L2 under t12, so it lies on the
// two circles of the inscribed-angle theorem (003 eqs. (6)-(7)); they meet in
// L1 and in the robot, the mirror image of L1 in the line of the centres.
// Only a starting point for the exact Newton solve (the cameras sit b_r off
// the centre).
std::optional<TPose2D> resectionAtCentre(const TObservation& o, const TMeasurement& z,
                                         const std::vector<TLandmark>& lms,
                                         const TCameraRig& rig) {
    TPoint2D L[3];
    double b[3];
    for (int k = 0; k < 3; k++) {
        const TLandmark& l = lms[size_t(o.lm[size_t(k)])];
        L[k] = {l.x, l.y};
        const int side = k < 2 ? o.side : -o.side;
        b[k] = o.pan[size_t(camIndex(side))] - std::atan(z[size_t(k)] / rig.focal);
    }
    auto centre = [](const TPoint2D& a, const TPoint2D& c,
                     double theta) -> std::optional<TPoint2D> {
        const double s = std::sin(theta);
        if (std::abs(s) < 1e-9)
            return std::nullopt;
        const double dx = c.x - a.x, dy = c.y - a.y;
        const double k = 0.5 * std::cos(theta) / s;  // (d / 2) cot(theta) / d
        return TPoint2D{(a.x + c.x) / 2 - k * dy, (a.y + c.y) / 2 + k * dx};
    };
    const auto c01 = centre(L[0], L[1], wrap(b[1] - b[0]));
    const auto c12 = centre(L[1], L[2], wrap(b[2] - b[1]));
    if (!c01 || !c12)
        return std::nullopt;
    const double ux = c12->x - c01->x, uy = c12->y - c01->y, uu = ux * ux + uy * uy;
    if (uu < 1e-18)
        return std::nullopt;
    const double t = ((L[1].x - c01->x) * ux + (L[1].y - c01->y) * uy) / uu;
    const TPoint2D f{c01->x + t * ux, c01->y + t * uy};  // foot of L1 on the line
    const TPoint2D p{2 * f.x - L[1].x, 2 * f.y - L[1].y};
    if (std::hypot(p.x - L[1].x, p.y - L[1].y) < 1e-9)
        return std::nullopt;
    // Heading: the world bearing of L0 minus its measured robot-frame bearing.
    return TPose2D{p.x, p.y, wrap(std::atan2(L[0].y - p.y, L[0].x - p.x) - b[0])};
}

std::optional<TPose2D> newtonThreeLandmark(const TBearings& eq, const TPose2D& start) {
    TPose2D p = start;
    double r[3], J[3][3];
    auto norm = [](const double v[3]) {
        return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    };
    eq.eval(p, r, J);
    for (int it = 0; it < 60; it++) {
        if (norm(r) < 1e-14)
            break;
        // Singular when robot and landmarks lie on one circle (or line):
        // the bearings then do not fix the pose. Scale-free test on the
        // determinant relative to the rows' sizes; below 1e-6 a pixel's error
        // would move the pose by metres, so such geometry counts as
        // degenerate rather than as a (useless) solution.
        const double rows = norm(J[0]) * norm(J[1]) * norm(J[2]);
        const double D = det3(J);
        if (!(std::abs(D) > 1e-6 * rows))
            return std::nullopt;
        // Cramer's rule for J d = -r.
        double d[3];
        for (int c = 0; c < 3; c++) {
            double M[3][3];
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    M[i][j] = j == c ? -r[i] : J[i][j];
            d[c] = det3(M) / D;
        }
        if (std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]) < 1e-14)
            break;  // converged
        // Damped step: halve (a few times) until the residual shrinks.
        const double n0 = norm(r);
        double lam = 1, rq[3], Jq[3][3];
        TPose2D q;
        bool descended = false;
        for (int h = 0; h < 12 && !descended; h++, lam /= 2) {
            q = {p.x + lam * d[0], p.y + lam * d[1], wrap(p.phi + lam * d[2])};
            eq.eval(q, rq, Jq);
            descended = norm(rq) < n0;
        }
        if (!descended)
            break;  // no descent left: converged as far as doubles allow
        p = q;
        std::copy(rq, rq + 3, r);
        std::copy(&Jq[0][0], &Jq[0][0] + 9, &J[0][0]);
    }
    if (!(norm(r) < 1e-9))
        return std::nullopt;
    return p;
}

std::optional<TPose2D> solveThreeLandmark(const TObservation& o, const TMeasurement& z,
                                          const std::vector<TLandmark>& lms,
                                          const TCameraRig& rig, const TPose2D& prior) {
    // Newton from the dead-reckoning prior (its basin holds the solution the
    // robot is at: with the cameras off the centre the bearing equations can
    // have others); from the closed-form resection when that does not
    // converge.
    const TBearings eq(o, z, lms, rig);
    if (const auto p = newtonThreeLandmark(eq, prior))
        return p;
    if (const auto init = resectionAtCentre(o, z, lms, rig))
        return newtonThreeLandmark(eq, *init);
    return std::nullopt;
}
}  // namespace

TPoint2D cameraCentre(const TPose2D& robot, int side, double b_r) {
    return {robot.x - side * b_r * std::sin(robot.phi),
            robot.y + side * b_r * std::cos(robot.phi)};
}

std::pair<double, double> project(const TPoint2D& c, double psi, const TPoint2D& q,
                                  double f) {
    const double rx = q.x - c.x, ry = q.y - c.y;
    const double t = rx * std::cos(psi) + ry * std::sin(psi);
    const double s = rx * std::sin(psi) - ry * std::cos(psi);
    return {f * s / t, t};
}

std::pair<TPoint2D, TPoint2D> landmarkEnds(const TLandmark& l) {
    const double tx = -std::sin(l.facing), ty = std::cos(l.facing);
    return {{l.x + l.radius * tx, l.y + l.radius * ty},
            {l.x - l.radius * tx, l.y - l.radius * ty}};
}

std::optional<std::pair<double, double>> parallelStereo(double uL, double uR, double b,
                                                        double f) {
    const double d = uL - uR;
    if (!(d > 0))
        return std::nullopt;
    return std::make_pair(b * f / d, b * (uL + uR) / (2 * d));
}

TMeasurement predictMeasurement(const TObservation& o, const TPose2D& pose,
                                const std::vector<TLandmark>& lms,
                                const TCameraRig& rig) {
    const double f = rig.focal;
    auto uOf = [&](int side, const TPoint2D& q) {
        return project(cameraCentre(pose, side, rig.b_r),
                       pose.phi + o.pan[size_t(camIndex(side))], q, f);
    };
    switch (o.strategy) {
        case TStrategy::Stereo: {
            const auto [ep, em] = landmarkEnds(lms[size_t(o.lm[0])]);
            TMeasurement z;
            for (int side : {+1, -1}) {
                const double up = uOf(side, ep).first, um = uOf(side, em).first;
                z.push_back((up + um) / 2);
                z.push_back((up - um) / 2);
            }
            return z;
        }
        case TStrategy::TwoLandmark: {
            const TLandmark& lj = lms[size_t(o.lm[0])];
            const TLandmark& li = lms[size_t(o.lm[1])];
            const auto [uj, tj] = uOf(o.side, {lj.x, lj.y});
            return {uj, f * lj.radius / tj, uOf(-o.side, {li.x, li.y}).first};
        }
        case TStrategy::ThreeLandmark:
        default: {
            TMeasurement z;
            for (int k = 0; k < 3; k++) {
                const TLandmark& l = lms[size_t(o.lm[size_t(k)])];
                z.push_back(uOf(k < 2 ? o.side : -o.side, {l.x, l.y}).first);
            }
            return z;
        }
    }
}

std::optional<TPose2D> solvePose(const TObservation& o, const TMeasurement& z,
                                 const std::vector<TLandmark>& lms, const TCameraRig& rig,
                                 const TPose2D& prior) {
    for (double v : z)
        if (!std::isfinite(v))
            return std::nullopt;
    std::optional<TPose2D> p;
    switch (o.strategy) {
        case TStrategy::Stereo:
            p = solveStereo(o, z, lms, rig);
            break;
        case TStrategy::TwoLandmark:
            p = solveTwoLandmark(o, z, lms, rig, prior);
            break;
        case TStrategy::ThreeLandmark:
            p = solveThreeLandmark(o, z, lms, rig, prior);
            break;
    }
    if (p && !(std::isfinite(p->x) && std::isfinite(p->y) && std::isfinite(p->phi)))
        return std::nullopt;
    return p;
}

std::vector<double> measurementErrors(const TObservation& o, const TImageErrors& e) {
    switch (o.strategy) {
        case TStrategy::Stereo:
            return {e.du, e.dr, e.du, e.dr};
        case TStrategy::TwoLandmark:
            return {e.du, e.dr, e.du};
        case TStrategy::ThreeLandmark:
        default:
            return {e.du, e.du, e.du};
    }
}

TWorstCase worstCaseError(const TObservation& o, const TPose2D& pose,
                          const std::vector<TLandmark>& lms, const TCameraRig& rig,
                          const TImageErrors& e,
                          const std::function<bool(double, double)>& giveUp) {
    TWorstCase w;
    const TMeasurement z0 = predictMeasurement(o, pose, lms, rig);
    const auto p0 = solvePose(o, z0, lms, rig, pose);
    if (!p0 || std::hypot(p0->x - pose.x, p0->y - pose.y) > 1e-6 ||
        std::abs(wrap(p0->phi - pose.phi)) > 1e-6)
        return w;
    const std::vector<double> dz = measurementErrors(o, e);
    const size_t n = dz.size();
    TMeasurement z(n);
    for (unsigned mask = 0; mask < (1u << n); mask++) {
        for (size_t k = 0; k < n; k++)
            z[k] = z0[k] + ((mask >> k) & 1 ? dz[k] : -dz[k]);
        const auto p = solvePose(o, z, lms, rig, pose);
        if (!p)
            return w;
        w.ePos = std::max(w.ePos, std::hypot(p->x - pose.x, p->y - pose.y));
        w.dPhi = std::max(w.dPhi, std::abs(wrap(p->phi - pose.phi)));
        if (giveUp && mask + 1 < (1u << n) && giveUp(w.ePos, w.dPhi)) {
            w.gaveUp = true;
            return w;
        }
    }
    w.ok = true;
    return w;
}

std::vector<TLandmarkView> landmarkViews(const TPose2D& pose,
                                         const std::vector<TLandmark>& lms,
                                         const TCameraRig& rig,
                                         const geometry::CSegmentIndex& occluders) {
    std::vector<TLandmarkView> views(lms.size());
    const double cosMax = std::cos(rig.maxIncidence);
    const double fitPx = std::min(rig.width, rig.height) / 2.0;
    for (size_t i = 0; i < lms.size(); i++) {
        const TLandmark& l = lms[i];
        TLandmarkView& v = views[i];
        v.distCentre = std::hypot(l.x - pose.x, l.y - pose.y);
        if (v.distCentre > rig.maxRange + rig.b_r)
            continue;  // cheap reject before the per-camera tests
        for (int side : {+1, -1}) {
            const size_t k = size_t(camIndex(side));
            const TPoint2D c = cameraCentre(pose, side, rig.b_r);
            const double rx = l.x - c.x, ry = l.y - c.y, d = std::hypot(rx, ry);
            v.dist[k] = d;
            if (!(d > 1e-6) || d > rig.maxRange)
                continue;
            if ((-rx * std::cos(l.facing) - ry * std::sin(l.facing)) / d < cosMax)
                continue;  // the back side, or too oblique
            const double pan = wrap(std::atan2(ry, rx) - pose.phi);
            if (std::abs(pan) > rig.panLimit)
                continue;
            if (rig.focal * l.radius / d > fitPx)
                continue;  // too near: the landmark does not fit the image
            // Line of sight, stopped just short of the landmark's own wall.
            const double back = std::min(0.01, d / 2);
            if (occluders.anyWithin(c, {l.x - back * rx / d, l.y - back * ry / d}, 0))
                continue;
            v.visible[k] = true;
            v.pan[k] = pan;
        }
    }
    return views;
}

std::vector<TObservation> enumerateObservations(const TPose2D& pose,
                                                const std::vector<TLandmark>& lms,
                                                const std::vector<TLandmarkView>& views,
                                                const TCameraRig& rig) {
    std::vector<TObservation> out;
    const double halfW = rig.width / 2.0, halfH = rig.height / 2.0, f = rig.focal;
    const size_t n = lms.size();
    // A: both cameras parallel, aimed from the robot centre at the landmark.
    for (size_t i = 0; i < n; i++) {
        if (!views[i].visible[0] || !views[i].visible[1])
            continue;
        const TLandmark& l = lms[i];
        const double pan = wrap(std::atan2(l.y - pose.y, l.x - pose.x) - pose.phi);
        if (std::abs(pan) > rig.panLimit)
            continue;
        const auto [ep, em] = landmarkEnds(l);
        bool fits = true;
        for (int side : {+1, -1}) {
            const TPoint2D c = cameraCentre(pose, side, rig.b_r);
            for (const TPoint2D& q : {ep, em}) {
                const auto [u, t] = project(c, pose.phi + pan, q, f);
                fits = fits && t > 0 && std::abs(u) <= halfW && f * l.radius / t <= halfH;
            }
        }
        if (!fits)
            continue;
        TObservation o;
        o.strategy = TStrategy::Stereo;
        o.lm = {{int(i), -1, -1}};
        o.pan = {{pan, pan}};
        out.push_back(o);
    }
    // B: the nearer landmark j by one camera, the other i by the other camera.
    for (size_t j = 0; j < n; j++)
        for (size_t i = 0; i < n; i++) {
            if (i == j)
                continue;
            const bool nearer = views[j].distCentre < views[i].distCentre ||
                                (views[j].distCentre == views[i].distCentre && j < i);
            if (!nearer)
                continue;
            for (int side : {+1, -1}) {
                const size_t kn = size_t(camIndex(side)), kf = size_t(camIndex(-side));
                if (!views[j].visible[kn] || !views[i].visible[kf])
                    continue;
                TObservation o;
                o.strategy = TStrategy::TwoLandmark;
                o.lm = {{int(j), int(i), -1}};
                o.side = side;
                o.pan[kn] = views[j].pan[kn];
                o.pan[kf] = views[i].pan[kf];
                out.push_back(o);
            }
        }
    // C: a pair in one camera's image, the third landmark in the other's.
    for (int side : {+1, -1}) {
        const size_t kp = size_t(camIndex(side)), ks = size_t(camIndex(-side));
        const TPoint2D c = cameraCentre(pose, side, rig.b_r);
        for (size_t a = 0; a < n; a++) {
            if (!views[a].visible[kp])
                continue;
            for (size_t b = a + 1; b < n; b++) {
                if (!views[b].visible[kp])
                    continue;
                const double pan = wrap(views[a].pan[kp] +
                                        wrap(views[b].pan[kp] - views[a].pan[kp]) / 2);
                if (std::abs(pan) > rig.panLimit)
                    continue;
                bool fits = true;
                for (size_t m : {a, b}) {
                    const auto [u, t] =
                        project(c, pose.phi + pan, {lms[m].x, lms[m].y}, f);
                    const double rImg = f * lms[m].radius / t;
                    fits = fits && t > 0 && std::abs(u) + rImg <= halfW && rImg <= halfH;
                }
                if (!fits)
                    continue;
                for (size_t s = 0; s < n; s++) {
                    if (s == a || s == b || !views[s].visible[ks])
                        continue;
                    TObservation o;
                    o.strategy = TStrategy::ThreeLandmark;
                    o.lm = {{int(a), int(b), int(s)}};
                    o.side = side;
                    o.pan[kp] = pan;
                    o.pan[ks] = views[s].pan[ks];
                    out.push_back(o);
                }
            }
        }
    }
    return out;
}

}  // namespace risknav::viewpoint
