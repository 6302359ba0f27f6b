#include <risknav/mapping/CLocalProbGrid.h>

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
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
    std::vector<float> p(m_p.size(), 0.5f);
    std::vector<uint16_t> c(m_count.size(), 0);
    for (int j = 0; j < m_n; j++) {
        const int sj = j + dj;
        if (sj < 0 || sj >= m_n)
            continue;
        for (int i = 0; i < m_n; i++) {
            const int si = i + di;
            if (si < 0 || si >= m_n)
                continue;
            p[index(i, j)] = m_p[index(si, sj)];
            c[index(i, j)] = m_count[index(si, sj)];
        }
    }
    m_p.swap(p);
    m_count.swap(c);
    m_x0 += di * m_res;
    m_y0 += dj * m_res;
    return {di, dj};
}

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
    const double step = nRays > 1 ? aperture / double(nRays - 1) : aperture;
    const double maxRange = scan.maxRange;
    const double reach = maxRange + m.delta(maxRange);
    // MRPT's ray order: right to left, or mirrored.
    const double sign = scan.rightToLeft ? 1.0 : -1.0;
    const int i0 = std::max(0, x2idx(sx - reach)),
              i1 = std::min(m_n - 1, x2idx(sx + reach));
    const int j0 = std::max(0, y2idx(sy - reach)),
              j1 = std::min(m_n - 1, y2idx(sy + reach));
    // cheap tests first (the cost is one atan2 per cell in reach): out of
    // reach by the squared distance; behind a sensor of <= 180 deg by the
    // sign of the forward component (those cells map to no ray either way)
    const double reach2 = reach * reach;
    const double cyaw = std::cos(syaw), sinyaw = std::sin(syaw);
    const bool halfPlane = aperture <= M_PI + 1e-9;
    const double behind = std::sin(0.5 * step);
    for (int j = j0; j <= j1; j++) {
        const double dy = idx2y(j) - sy;
        for (int i = i0; i <= i1; i++) {
            const double dx = idx2x(i) - sx;
            const double r2 = dx * dx + dy * dy;
            if (r2 > reach2)
                continue;
            const double r = std::sqrt(r2);
            if (halfPlane && dx * cyaw + dy * sinyaw < -r * behind)
                continue;
            // the ray whose angular sector holds the cell's bearing
            const double b = sign * mrpt::math::wrapToPi(std::atan2(dy, dx) - syaw);
            const double k = std::round((b + 0.5 * aperture) / step);
            long ray = long(k);
            if (aperture >= 2 * M_PI - 1e-9)
                ray = ((ray % long(nRays)) + long(nRays)) % long(nRays);
            if (ray < 0 || ray >= long(nRays))
                continue;
            int reading = -1;  // -1 none, 0 free, 1 occupied
            if (scan.getScanRangeValidity(size_t(ray))) {
                const double R = scan.getScanRange(size_t(ray));
                const double d = m.delta(R);
                if (r < R - d)
                    reading = 0;
                else if (r <= R + d)
                    reading = 1;
            } else if (r < maxRange) {
                reading = 0;
            }
            if (reading < 0)
                continue;
            const size_t idx = index(i, j);
            m_p[idx] = float(std::clamp(bayesUpdate(m_p[idx], reading == 1, m),
                                        kProbabilityMin, 1.0 - kProbabilityMin));
            if (m_count[idx] < 65535)
                m_count[idx]++;
        }
    }
}

void CLocalProbGrid::setCell(int i, int j, float p, uint16_t count) {
    m_p[index(i, j)] = p;
    m_count[index(i, j)] = count;
}

TCellClass classifyCell(float p, uint16_t observations, double occupiedThreshold,
                        double freeThreshold) {
    if (p > occupiedThreshold)
        return TCellClass::Obstacle;
    if (p < freeThreshold)
        return TCellClass::Free;
    return observations > 0 ? TCellClass::UndecidedObserved
                            : TCellClass::UndecidedUnobserved;
}
}  // namespace risknav::mapping
