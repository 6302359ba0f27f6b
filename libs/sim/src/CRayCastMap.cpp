#include <risknav/sim/CRayCastMap.h>

#include <cmath>

using mrpt::maps::COccupancyGridMap2D;

namespace risknav::sim {
namespace {
// The cell of g holding coordinate v along an axis starting at vMin: floored
// (MRPT's x2idx truncates, which puts a point just left of the map in cell 0).
int cellOf(double v, double vMin, double res) {
    return int(std::floor((v - vMin) / res));
}
}  // namespace

CRayCastMap::CRayCastMap(const COccupancyGridMap2D& map,
                         const mapping::TObstacleRule& rule)
    : m_grid(map) {
    const double res = map.getResolution();
    if (rule.outside_is_obstacle) {
        // resizeGrid keeps the map's cells where they are (the bounds are
        // whole cells) and adds one cell on each side
        const float r = map.getResolution();
        m_grid.resizeGrid(map.getXMin() - r, map.getXMax() + r, map.getYMin() - r,
                          map.getYMax() + r, 0.0f, false);
    }
    const COccupancyGridMap2D::cellType wall = COccupancyGridMap2D::p2l(0.0f),
                                        open = COccupancyGridMap2D::p2l(1.0f);
    const int nx = int(m_grid.getSizeX()), ny = int(m_grid.getSizeY());
    const int mx = int(map.getSizeX()), my = int(map.getSizeY());
    // Each cell takes the class of the map cell holding its centre (the same
    // cell, or the outside for the ring).
    for (int cy = 0; cy < ny; cy++) {
        const int sy = cellOf(m_grid.idx2y(cy), map.getYMin(), res);
        auto* row = m_grid.getRow(cy);
        for (int cx = 0; cx < nx; cx++) {
            const int sx = cellOf(m_grid.idx2x(cx), map.getXMin(), res);
            const bool onMap = sx >= 0 && sy >= 0 && sx < mx && sy < my;
            const bool obstacle =
                onMap ? rule.isObstacle(map.getCell(sx, sy)) : rule.outside_is_obstacle;
            row[cx] = obstacle ? wall : open;
        }
    }
}

bool CRayCastMap::isObstacleAt(double x, double y) const {
    const double res = m_grid.getResolution();
    const int cx = cellOf(x, m_grid.getXMin(), res),
              cy = cellOf(y, m_grid.getYMin(), res);
    if (cx < 0 || cy < 0 || cx >= int(m_grid.getSizeX()) || cy >= int(m_grid.getSizeY()))
        return false;
    return m_grid.getCell(cx, cy) < 0.5f;
}

}  // namespace risknav::sim
