#include <risknav/mapping/free_space.h>

#include <cmath>
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
    // fuseCells() of the two classes looked up in a table it fills (a
    // speed-up, the same cells)
    TFusedCell table[4][4];
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            table[a][b] = fuseCells(TCellClass(a), TCellClass(b));
    for (size_t k = 0; k < m.cells.size(); k++)
        m.cells[k] =
            table[int(classifyCell(pa[k], ca[k], occupiedThreshold, freeThreshold))]
                 [int(classifyCell(pb[k], cb[k], occupiedThreshold, freeThreshold))];
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
