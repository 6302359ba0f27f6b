#include <risknav/mapping/CLocalProbGrid.h>
#include <risknav/mapping/fast_atan2.h>

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace risknav::mapping {
CLocalProbGrid::CLocalProbGrid(int size, double resolution, double cx, double cy)
    : m_n(size), m_res(resolution) {
    if (size <= 0 || size > 4000 || !(resolution > 0))
        throw std::invalid_argument(
            "local grid: size must be in 1..4000, resolution > 0");
    m_x0 = cx - 0.5 * size * resolution;
    m_y0 = cy - 0.5 * size * resolution;
    m_p.assign(size_t(size) * size, 0.5f);
    m_count.assign(size_t(size) * size, 0);
}

int CLocalProbGrid::x2idx(double x) const {
    return int(std::floor((x - m_x0) / m_res));
}
int CLocalProbGrid::y2idx(double y) const {
    return int(std::floor((y - m_y0) / m_res));
}

std::pair<int, int> CLocalProbGrid::recenter(double x, double y) {
    const int di = x2idx(x) - m_n / 2, dj = y2idx(y) - m_n / 2;
    if (di == 0 && dj == 0)
        return {0, 0};
    // into the spare buffers (kept: no allocation per move), then swapped
    std::vector<float>& p = m_pSpare;
    std::vector<uint16_t>& c = m_countSpare;
    p.assign(m_p.size(), 0.5f);
    c.assign(m_count.size(), 0);
    // per row, the cells i with a source i + di inside: one contiguous copy
    const int iBegin = std::max(0, -di), iEnd = std::min(m_n, m_n - di);
    for (int j = 0; j < m_n && iBegin < iEnd; j++) {
        const int sj = j + dj;
        if (sj < 0 || sj >= m_n)
            continue;
        const size_t from = index(iBegin + di, sj), to = index(iBegin, j);
        const size_t len = size_t(iEnd - iBegin);
        std::copy_n(m_p.begin() + long(from), len, p.begin() + long(to));
        std::copy_n(m_count.begin() + long(from), len, c.begin() + long(to));
    }
    m_p.swap(p);
    m_count.swap(c);
    m_x0 += di * m_res;
    m_y0 += dj * m_res;
    return {di, dj};
}

namespace {
/** Which ray of a scan holds a cell: the ray whose angular sector holds the
 * cell's bearing from the sensor (the sector model's formula,
 * b = sign * wrapToPi(atan2 - yaw), ray = round(...)), with two speed-ups
 * that give the same rays (see fastRawRay() and walkRay()). */
struct TRayFinder {
    size_t nRays = 0;
    bool fullCircle = false;
    double sign = 1;  ///< MRPT's ray order: right to left, or mirrored
    double syaw = 0, aperture = 0, step = 0;
    double yawWrapped = 0, slack = 0;
    bool walk = false;  ///< walkRay() may be used
    long kLo = 0, kHi = -1;
    const double* boundX = nullptr;  ///< the sectors' edge directions, from kLo
    const double* boundY = nullptr;
    double crossTol = 0;
    static constexpr long kNoGuess = std::numeric_limits<long>::min();

    // a ray index, wrapped for a full circle; -1: no such ray
    long validRay(long ray) const {
        const long n = long(nRays);
        if (fullCircle) {
            // one turn either way without a division (most are), else modulo
            if (ray < 0 && ray >= -n)
                ray += n;
            else if (ray >= n && ray < 2 * n)
                ray -= n;
            else if (ray < 0 || ray >= n)
                ray = ((ray % n) + n) % n;
        }
        return ray < 0 || ray >= n ? -1 : ray;
    }
    long rayFromIndex(double x) const { return validRay(long(std::round(x))); }
    // the ray whose angular sector holds a bearing (-1: none)
    long exactRayOf(double dx, double dy) const {
        const double b = sign * mrpt::math::wrapToPi(std::atan2(dy, dx) - syaw);
        return rayFromIndex((b + 0.5 * aperture) / step);
    }
    // A speed-up giving the same rays: the polynomial atan2 is within
    // kFastAtan2MaxError of libm's, so its ray index is within `slack` of
    // the exact one; where that could round differently (near a sector
    // boundary, or near the +-pi wrap) the exact formula decides.
    // The unwrapped ray index (the exact one) from the fast guess, or false
    // where the guess could round differently.
    bool fastRawRay(double dx, double dy, long& raw) const {
        if (!(slack < 0.25))
            return false;
        double rel = fastAtan2(dy, dx) - yawWrapped;
        rel = rel > M_PI ? rel - 2 * M_PI : (rel < -M_PI ? rel + 2 * M_PI : rel);
        if (std::fabs(rel) > M_PI - 2 * slack * step)
            return false;
        const double x = (sign * rel + 0.5 * aperture) / step;
        const double fl = std::floor(x), off = x - fl;  // 0.5: a boundary
        if (std::fabs(off - 0.5) < slack)
            return false;
        // std::round(x) without its libm call: off is not near 0.5 here
        raw = long(fl) + (off > 0.5 ? 1 : 0);
        return true;
    }
    long rayOf(double dx, double dy) const {
        long raw;
        return fastRawRay(dx, dy, raw) ? validRay(raw) : exactRayOf(dx, dy);
    }
    // A second speed-up giving the same rays, along a row of cells: the ray
    // of the cell before is the guess, checked by the signs of two cross
    // products with the sector's boundary directions (no atan2, no
    // division). Boundary b sits at index x = kLo + b - 0.5, at bearing
    // syaw + sign * (x * step - aperture / 2). A cell v with
    // sign * cross(w_b, v) > tol and sign * cross(w_b+1, v) < -tol lies
    // strictly inside that sector (the sector is narrower than pi), at
    // least tol / |v| rad from its edges, where std::atan2's formula cannot
    // round it elsewhere; nearer an edge, or in a sector whose centre is
    // within 2 sectors of the +-pi wrap, rayOf() decides.
    long walkRay(double dx, double dy, double r, long& k) const {
        if (k != kNoGuess) {
            const double tol = crossTol * r;
            for (int tries = 0; tries < 4 && k > kLo && k < kHi; tries++) {
                const size_t b = size_t(k - kLo);
                const double lo = sign * (boundX[b] * dy - boundY[b] * dx);
                const double hi = sign * (boundX[b + 1] * dy - boundY[b + 1] * dx);
                if (std::fabs(lo) <= tol || std::fabs(hi) <= tol)
                    break;  // at an edge
                if (lo > 0 && hi < 0) {
                    const double centre = sign * (double(k) * step - 0.5 * aperture);
                    if (std::fabs(centre) <= M_PI - 2 * step)
                        return validRay(k);
                    break;  // near the wrap
                }
                k += lo < 0 ? -1 : 1;
            }
        }
        long raw;
        if (fastRawRay(dx, dy, raw)) {
            k = raw;
            return validRay(raw);
        }
        k = kNoGuess;
        return exactRayOf(dx, dy);
    }
};

/** The ray finder of a scan whose sensor is at yaw `syaw`; the sectors'
 * edge directions go to boundX, boundY (kept by the caller). */
TRayFinder makeRayFinder(const mrpt::obs::CObservation2DRangeScan& scan, double syaw,
                         std::vector<double>& boundX, std::vector<double>& boundY) {
    TRayFinder f;
    f.nRays = scan.getScanSize();
    f.syaw = syaw;
    f.aperture = scan.aperture;
    f.step = f.nRays > 1 ? f.aperture / double(f.nRays - 1) : f.aperture;
    f.fullCircle = f.aperture >= 2 * M_PI - 1e-9;
    f.sign = scan.rightToLeft ? 1.0 : -1.0;
    const double step = f.step, aperture = f.aperture, sign = f.sign;
    f.yawWrapped = mrpt::math::wrapToPi(syaw);
    f.slack = (2 * kFastAtan2MaxError + 1e-12) / step;
    const bool walk = step >= 1e-3 && step <= M_PI / 4 && f.slack < 0.25;
    f.walk = walk;
    f.kLo = walk ? long(std::floor((0.5 * aperture - M_PI) / step)) - 3 : 0;
    f.kHi = walk ? long(std::ceil((0.5 * aperture + M_PI) / step)) + 3 : -1;
    boundX.clear();
    boundY.clear();
    for (long k = f.kLo; k <= f.kHi + 1; k++) {
        const double b = syaw + sign * ((double(k) - 0.5) * step - 0.5 * aperture);
        boundX.push_back(std::cos(b));
        boundY.push_back(std::sin(b));
    }
    f.boundX = boundX.data();
    f.boundY = boundY.data();
    // [rad]; the formulas err by ~1e-15, or by the rounding of a yaw of
    // large magnitude (an unwrapped one of 1e7 rad rounds by ~1e-9)
    const double big = std::fabs(syaw) + 2 * M_PI;
    f.crossTol = 1e-9 + 8 * (std::nextafter(big, 2 * big) - big);
    return f;
}

/** The rays that can hold a tile's cells, from the bearings of its corner
 * centres (one more each side for rounding): the farthest any of them
 * reads (`reach`, at most maxReach) and their nearest free bound (`free`,
 * -1: not known, or some candidate is no ray). `skip`: no ray's sector
 * reaches the tile. */
struct TTileRays {
    double reach = 0, free = -1;
    bool skip = false;
};
TTileRays tileRays(const TRayFinder& f, double xa, double xb, double ya, double yb,
                   double rMin2, double maxReach, bool fastCorners,
                   const std::vector<double>& rayOcc,
                   const std::vector<double>& rayFree) {
    const double sign = f.sign, syaw = f.syaw, aperture = f.aperture, step = f.step;
    TTileRays t;
    double& tileReach = t.reach;
    double& tileFree = t.free;
    tileReach = maxReach;
    if (rMin2 > 0) {
        // the sensor is outside the tile: its bearings span < pi
        double bLo = 1e9, bHi = -1e9;
        for (const double cx : {xa, xb})
            for (const double cy : {ya, yb}) {
                // the fast atan2 where it errs far less than the
                // ray each side added below
                const double a = fastCorners ? fastAtan2(cy, cx) : std::atan2(cy, cx);
                const double b = sign * mrpt::math::wrapToPi(a - syaw);
                bLo = std::min(bLo, b);
                bHi = std::max(bHi, b);
            }
        if (bHi - bLo < M_PI) {
            const long kLo = long(std::floor((bLo + 0.5 * aperture) / step)) - 1;
            const long kHi = long(std::ceil((bHi + 0.5 * aperture) / step)) + 1;
            tileReach = -1;  // then at most maxReach (<= reach)
            tileFree = std::numeric_limits<double>::infinity();
            for (long k = kLo; k <= kHi; k++) {
                const long ray = f.validRay(k);
                if (ray < 0) {
                    tileFree = -1;
                    continue;
                }
                tileReach = std::max(tileReach, std::min(maxReach, rayOcc[size_t(ray)]));
                if (tileFree >= 0)
                    tileFree = std::min(tileFree, double(rayFree[size_t(ray)]));
            }
            t.skip = tileReach < 0;  // no ray's sector reaches the tile
        }                            // else across the bearings' wrap: all rays
    }
    return t;
}
}  // namespace

void CLocalProbGrid::integrateScan(const mrpt::math::TPose2D& robot,
                                   const mrpt::obs::CObservation2DRangeScan& scan,
                                   const TSensorModel& m) {
    const size_t nRays = scan.getScanSize();
    if (nRays == 0)
        return;
    const auto& sp = scan.sensorPose;
    const double c = std::cos(robot.phi), s = std::sin(robot.phi);
    const double sx = robot.x + c * sp.x() - s * sp.y();
    const double sy = robot.y + s * sp.x() + c * sp.y();
    const double syaw = robot.phi + sp.yaw();
    const double aperture = scan.aperture;
    const double maxRange = scan.maxRange;
    const double reach = maxRange + m.delta(maxRange);
    const int i0 = std::max(0, x2idx(sx - reach)),
              i1 = std::min(m_n - 1, x2idx(sx + reach));
    const int j0 = std::max(0, y2idx(sy - reach)),
              j1 = std::min(m_n - 1, y2idx(sy + reach));
    if (i1 < i0 || j1 < j0)
        return;
    // per ray: the reading's bounds; m_rayOcc is also how far it reads at
    // all (no cell beyond it gets a reading from that ray)
    m_rayValid.resize(nRays);
    m_rayFree.resize(nRays);
    m_rayOcc.resize(nRays);
    for (size_t k = 0; k < nRays; k++) {
        m_rayValid[k] = scan.getScanRangeValidity(k);
        if (m_rayValid[k]) {
            const double R = scan.getScanRange(k), d = m.delta(R);
            m_rayFree[k] = R - d;
            m_rayOcc[k] = R + d;
        } else {
            m_rayFree[k] = m_rayOcc[k] = maxRange;
        }
    }
    const TRayFinder finder = makeRayFinder(scan, syaw, m_boundX, m_boundY);
    const double step = finder.step;
    const bool walk = finder.walk;
    constexpr long kNoGuess = TRayFinder::kNoGuess;
    // cheap tests first (the cost is one atan2 per cell): out of reach by the
    // squared distance; behind a sensor of <= 180 deg by the sign of the
    // forward component (those cells map to no ray either way)
    const double cyaw = std::cos(syaw), sinyaw = std::sin(syaw);
    const bool halfPlane = aperture <= M_PI + 1e-9;
    const double behind = std::sin(0.5 * step);
    // Tiles of cells: from the bearings of a tile's corner centres, the rays
    // that can hold its cells (one more each side for rounding) and the
    // farthest any of them reads; a tile, or a cell, beyond that is skipped
    // without its atan2 (most cells lie behind walls). A speed-up only: each
    // cell still gets its own ray as above.
    constexpr int kTile = 8;
    const bool fastCorners = kFastAtan2MaxError < 0.1 * step;
    const double maxReach =
        std::min(reach, *std::max_element(m_rayOcc.begin(), m_rayOcc.end()));
    // one reading of cell (i, j): the Bayes update, its count
    auto read = [&](int i, int j, bool occupied) {
        const size_t idx = index(i, j);
        m_p[idx] = float(std::clamp(bayesUpdate(m_p[idx], occupied, m), kProbabilityMin,
                                    1.0 - kProbabilityMin));
        if (m_count[idx] < 65535)
            m_count[idx]++;
    };
    long rowGuess[kTile];  // per row of a band of tiles: the ray of the cell before
    for (int tj = j0; tj <= j1; tj += kTile) {
        std::fill(std::begin(rowGuess), std::end(rowGuess), kNoGuess);
        for (int ti = i0; ti <= i1; ti += kTile) {
            const int tiEnd = std::min(i1, ti + kTile - 1),
                      tjEnd = std::min(j1, tj + kTile - 1);
            const double xa = idx2x(ti) - sx, xb = idx2x(tiEnd) - sx;
            const double ya = idx2y(tj) - sy, yb = idx2y(tjEnd) - sy;
            const double nx = xa > 0 ? xa : (xb < 0 ? xb : 0.0);
            const double ny = ya > 0 ? ya : (yb < 0 ? yb : 0.0);
            const double rMin2 = nx * nx + ny * ny;
            const TTileRays tr = tileRays(finder, xa, xb, ya, yb, rMin2, maxReach,
                                          fastCorners, m_rayOcc, m_rayFree);
            if (tr.skip)
                continue;
            const double tileReach = tr.reach;
            // the nearest free bound of the tile's candidate rays (-1: not
            // known, or some candidate is no ray): a tile nearer than it is
            // read free in every cell, whichever ray the cell falls in
            const double tileFree = tr.free;
            if (rMin2 > tileReach * tileReach)
                continue;
            // A speed-up giving the same readings: a tile nearer than every
            // candidate ray's free bound, and within the tile's reach (beyond
            // it a cell is skipped), reads free in every cell without finding
            // its ray (the farthest cell centre's r, computed as below, is the
            // largest: dx, dy are monotone in i, j). Each of its cells falls
            // in a candidate ray, all of them rays, so none lies behind the
            // sensor either.
            if (tileFree > 0) {
                const double fx = std::max(xa * xa, xb * xb),
                             fy = std::max(ya * ya, yb * yb);
                if (std::sqrt(fx + fy) < tileFree && fx + fy <= tileReach * tileReach) {
                    for (int j = tj; j <= tjEnd; j++)
                        for (int i = ti; i <= tiEnd; i++)
                            read(i, j, false);
                    continue;
                }
            }
            const double tileReach2 = tileReach * tileReach;
            for (int j = tj; j <= tjEnd; j++) {
                const double dy = idx2y(j) - sy;
                long& guess = rowGuess[j - tj];
                for (int i = ti; i <= tiEnd; i++) {
                    const double dx = idx2x(i) - sx;
                    const double r2 = dx * dx + dy * dy;
                    if (r2 > tileReach2)
                        continue;
                    const double r = std::sqrt(r2);
                    if (halfPlane && dx * cyaw + dy * sinyaw < -r * behind)
                        continue;
                    const long ray =
                        walk ? finder.walkRay(dx, dy, r, guess) : finder.rayOf(dx, dy);
                    if (ray < 0)
                        continue;
                    // free when nearer than R - delta, occupied up to R + delta;
                    // a ray without a return reads free up to maxRange
                    bool occupied;
                    if (m_rayValid[size_t(ray)]) {
                        if (r < m_rayFree[size_t(ray)])
                            occupied = false;
                        else if (r <= m_rayOcc[size_t(ray)])
                            occupied = true;
                        else
                            continue;
                    } else if (r < maxRange) {
                        occupied = false;
                    } else {
                        continue;
                    }
                    read(i, j, occupied);
                }
            }
        }
    }
}

void CLocalProbGrid::setCell(int i, int j, float p, uint16_t count) {
    m_p[index(i, j)] = p;
    m_count[index(i, j)] = count;
}

}  // namespace risknav::mapping
