#pragma once
// Hand-made fused free-space maps for the M1 unit tests (header only: the
// test executables that include it link risknav::mapping).
#include <risknav/mapping/free_space.h>

#include <cmath>

namespace risknav::test {
/** A map of `size` m a side, 5 cm cells, centred on (cx, cy), all `fill`. */
inline mapping::TFreeSpaceMap localMap(double cx, double cy, double size,
                                       mapping::TFusedCell fill) {
    mapping::TFreeSpaceMap m;
    m.resolution = 0.05;
    m.size = int(std::lround(size / m.resolution));
    m.xMin = cx - 0.5 * size;
    m.yMin = cy - 0.5 * size;
    m.cells.assign(size_t(m.size) * m.size, fill);
    return m;
}

/** Sets the cells whose centres lie in [x0, x1] x [y0, y1] to `c`. */
inline void fillRect(mapping::TFreeSpaceMap& m, double x0, double y0, double x1,
                     double y1, mapping::TFusedCell c) {
    for (int j = 0; j < m.size; j++)
        for (int i = 0; i < m.size; i++)
            if (m.idx2x(i) >= x0 && m.idx2x(i) <= x1 && m.idx2y(j) >= y0 &&
                m.idx2y(j) <= y1)
                m.cells[m.index(i, j)] = c;
}
}  // namespace risknav::test
