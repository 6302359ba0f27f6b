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
    // classifyCell() and fuseCells() without branches (a speed-up, the same
    // cells): each class as its enum's number, the pair looked up in a table
    // that fuseCells() fills
    TFusedCell table[4][4];
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            table[a][b] = fuseCells(TCellClass(a), TCellClass(b));
    auto code = [&](float p, uint16_t n) {
        const double d = p;
        const int obstacle = d > occupiedThreshold, free = d < freeThreshold;
        const int undecided = uint8_t(n > 0 ? TCellClass::UndecidedObserved
                                            : TCellClass::UndecidedUnobserved);
        return obstacle ? int(TCellClass::Obstacle)
                        : (free ? int(TCellClass::Free) : undecided);
    };
    for (size_t k = 0; k < m.cells.size(); k++)
        m.cells[k] = table[code(pa[k], ca[k])][code(pb[k], cb[k])];
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
