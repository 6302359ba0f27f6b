#pragma once
#include <risknav/mapping/CLocalProbGrid.h>

#include <mrpt/maps/COccupancyGridMap2D.h>

#include <cstdint>
#include <vector>

namespace risknav::mapping {
/** A cell of the fused free-space map. The paper plans on free / occupied;
 * the speed controller also needs to know which non-free cells are
 * undecided (the distance d of (000) section 3). */
enum class TFusedCell : uint8_t { Free, Obstacle, Undecided };

/** Two-sensor fusion of (000) section 2: free if both sensors say free, or
 * one says free and the other undecided-with-observation; otherwise not free
 * (occupied for planning): Obstacle if either says obstacle, else Undecided. */
inline TFusedCell fuseCells(TCellClass a, TCellClass b) {
    const auto freeWith = [](TCellClass x, TCellClass y) {
        return x == TCellClass::Free &&
               (y == TCellClass::Free || y == TCellClass::UndecidedObserved);
    };
    if (freeWith(a, b) || freeWith(b, a))
        return TFusedCell::Free;
    if (a == TCellClass::Obstacle || b == TCellClass::Obstacle)
        return TFusedCell::Obstacle;
    return TFusedCell::Undecided;
}

/** The free-space map of one cycle, on the grids' cells. */
struct TFreeSpaceMap {
    int size = 0;
    double resolution = 0.05;
    double xMin = 0, yMin = 0;  ///< ego-frame corner of cell (0, 0)
    std::vector<TFusedCell> cells;
    size_t index(int i, int j) const { return size_t(j) * size + i; }
    bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < size && j < size; }
    int x2idx(double x) const;
    int y2idx(double y) const;
    double idx2x(int i) const { return xMin + (i + 0.5) * resolution; }
    double idx2y(int j) const { return yMin + (j + 0.5) * resolution; }
    TFusedCell at(int i, int j) const {
        return inside(i, j) ? cells[index(i, j)] : TFusedCell::Undecided;
    }
};

/** Classifies both grids (thresholds of (000): occupied 0.7, free 0.2) and
 * fuses them cell by cell. The grids must share size, resolution and origin
 * (throws std::invalid_argument). One sensor: pass its grid twice. */
TFreeSpaceMap fuseGrids(const CLocalProbGrid& a, const CLocalProbGrid& b,
                        double occupiedThreshold, double freeThreshold);

/** The map as an MRPT grid (P(free): 1 free, 0 obstacle, 0.5 undecided), for
 * images and for MRPT tools. */
mrpt::maps::COccupancyGridMap2D toMrptGrid(const TFreeSpaceMap& m);
}  // namespace risknav::mapping
