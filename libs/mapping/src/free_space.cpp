#include <risknav/mapping/free_space.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace risknav::mapping {
int TFreeSpaceMap::x2idx(double x) const {
    return int(std::floor((x - xMin) / resolution));
}
int TFreeSpaceMap::y2idx(double y) const {
    return int(std::floor((y - yMin) / resolution));
}

TFreeSpaceMap fuseGrids(const CLocalProbGrid& a, const CLocalProbGrid& b,
                        double occupiedThreshold, double freeThreshold) {
    if (a.size() != b.size() || a.resolution() != b.resolution() ||
        a.xMin() != b.xMin() || a.yMin() != b.yMin())
        throw std::invalid_argument("fuseGrids: the two grids do not share their cells");
    TFreeSpaceMap m;
    m.size = a.size();
    m.resolution = a.resolution();
    m.xMin = a.xMin();
    m.yMin = a.yMin();
    m.cells.resize(a.probabilities().size());
    const auto& pa = a.probabilities();
    const auto& pb = b.probabilities();
    const auto& ca = a.counts();
    const auto& cb = b.counts();
    // fuseCells() without branches or look-ups, per cell on 0/1 bytes (a
    // speed-up: the loop vectorizes; the same cells, checked against
    // fuseCells() in the tests): p > occupied is an obstacle; else p >=
    // free (not p < free: P is never NaN) is undecided, observed or not.
    // The thresholds as floats that compare the same: p > t iff p >= the
    // least float above t, p < t iff p <= the greatest float below t.
    static_assert(uint8_t(TFusedCell::Free) == 0 && uint8_t(TFusedCell::Obstacle) == 1 &&
                  uint8_t(TFusedCell::Undecided) == 2);
    auto floatAbove = [](double t) {
        const float x = float(t);
        return double(x) > t ? x
                             : std::nextafter(x, std::numeric_limits<float>::infinity());
    };
    auto floatBelow = [](double t) {
        const float x = float(t);
        return double(x) < t ? x
                             : std::nextafter(x, -std::numeric_limits<float>::infinity());
    };
    const float occ = floatAbove(occupiedThreshold), fr = floatBelow(freeThreshold);
    const float* fa = pa.data();
    const float* fb = pb.data();
    const uint16_t* na = ca.data();
    const uint16_t* nb = cb.data();
    auto* out = reinterpret_cast<uint8_t*>(m.cells.data());
    for (size_t k = 0, n = m.cells.size(); k < n; k++) {
        const float a = fa[k], b = fb[k];
        const uint8_t obstA = a >= occ, obstB = b >= occ;
        // 0/1 flags combined bitwise (1 ^ x: not x)
        const uint8_t freeA = (1 ^ obstA) & (a <= fr), freeB = (1 ^ obstB) & (b <= fr);
        // undecided with an observation: neither obstacle nor free, seen
        const uint8_t seenA = (1 ^ (obstA | freeA)) & (na[k] > 0);
        const uint8_t seenB = (1 ^ (obstB | freeB)) & (nb[k] > 0);
        const uint8_t isFree = (freeA & (freeB | seenB)) | (freeB & seenA);
        const uint8_t isObst = (1 ^ isFree) & (obstA | obstB);
        out[k] = uint8_t((1 ^ isFree) * (2 - isObst));
    }
    return m;
}

mrpt::maps::COccupancyGridMap2D toMrptGrid(const TFreeSpaceMap& m) {
    const double ext = m.size * m.resolution;
    mrpt::maps::COccupancyGridMap2D g(float(m.xMin), float(m.xMin + ext), float(m.yMin),
                                      float(m.yMin + ext), float(m.resolution));
    const int w = int(g.getSizeX()), h = int(g.getSizeY());
    for (int j = 0; j < h && j < m.size; j++)
        for (int i = 0; i < w && i < m.size; i++) {
            const TFusedCell c = m.cells[m.index(i, j)];
            g.setCell(i, j,
                      c == TFusedCell::Free       ? 1.0f
                      : c == TFusedCell::Obstacle ? 0.0f
                                                  : 0.5f);
        }
    return g;
}
}  // namespace risknav::mapping
