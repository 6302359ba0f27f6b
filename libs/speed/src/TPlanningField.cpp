#include <risknav/speed/TPlanningField.h>

#include <risknav/mapping/distance_transform.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace risknav::speed {
using mapping::TFusedCell;

namespace {
/** Distance [m] from every cell to the nearest cell where `source` is set,
 * measured to that cell's near edge (centre distance - half a cell: a robot
 * disc at a cell centre with radius below this does not touch it);
 * `borderIsSource`: the ring outside the grid counts as a source. The
 * centre distance is the float square root of the exact squared one (what
 * OpenCV's precise transform, used here before, gives). */
std::vector<float> distanceTo(const std::vector<uint8_t>& source, int n, double res,
                              bool borderIsSource) {
    std::vector<int32_t> d2;
    mapping::squaredDistanceTransform(source, n, n, borderIsSource, d2);
    // one source anywhere gives every cell a distance: none, or all
    if (d2.empty() || d2[0] == mapping::kNoSource)
        return std::vector<float>(d2.size(), std::numeric_limits<float>::infinity());
    std::vector<float> out(d2.size());
    for (size_t k = 0; k < d2.size(); k++)
        out[k] = float(std::max(0.0, (double(std::sqrt(float(d2[k]))) - 0.5) * res));
    return out;
}
}  // namespace

double TPlanningField::clearanceAt(double x, double y) const {
    const int i = map.x2idx(x), j = map.y2idx(y);
    return map.inside(i, j) ? clearance[map.index(i, j)] : 0.0;
}

TPlanningField computePlanningField(const mapping::TFreeSpaceMap& map,
                                    double minOpening) {
    TPlanningField f;
    f.map = map;
    const int n = map.size;
    // wayOn: the frontier cells, then (below) only the open ones and the ring
    std::vector<uint8_t> blocked(map.cells.size()), wayOn(map.cells.size(), 0);
    for (size_t k = 0; k < map.cells.size(); k++)
        blocked[k] = map.cells[k] != TFusedCell::Free;
    const TFusedCell* cells = map.cells.data();
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const size_t k = map.index(i, j);
            if (cells[k] != TFusedCell::Undecided)
                continue;
            auto freeAt = [&](size_t nk) { return cells[nk] == TFusedCell::Free; };
            if ((i + 1 < n && freeAt(k + 1)) || (i > 0 && freeAt(k - 1)) ||
                (j + 1 < n && freeAt(k + size_t(n))) || (j > 0 && freeAt(k - size_t(n))))
                wayOn[k] = 1;
        }
    f.clearance = distanceTo(blocked, n, map.resolution, true);
    // The ways on, for the choice of a temporary destination: open frontier
    // cells, and the grid's outer ring, whose free cells lead on into what the
    // robot-centred grid no longer (or not yet) holds
    // "Nearer than minOpening to an obstacle cell", measured as distanceTo()
    // measures (centre to near edge, sqrtf of the exact squared centre
    // distance) but only where it decides something (frontier and ring
    // cells). The offsets (di, dj) that measure less than minOpening are, for
    // each di, the interval |dj| <= reachDj[reach + di] (-1: none), as the
    // distance is monotone in di^2 + dj^2; a cell is near an obstacle iff
    // for some di the column i + di has an obstacle cell within that many
    // rows: one look-up per di in the column distances below (a speed-up of
    // the full distance transform, then of a disc search, this took; the
    // same cells pass).
    int reach = -1;
    std::vector<int> reachDj;
    if (minOpening > 0) {
        const double res = map.resolution;
        auto measured = [&](int d2) {
            return float(std::max(0.0, (double(std::sqrt(float(d2))) - 0.5) * res));
        };
        reach = int(std::ceil(minOpening / res + 1.5));
        reachDj.assign(size_t(2 * reach + 1), -1);
        for (int di = -reach; di <= reach; di++)
            for (int dj = 0; dj <= reach; dj++)
                if (measured(di * di + dj * dj) < minOpening)
                    reachDj[size_t(di + reach)] = dj;
    }
    // colNear: rows from cell (i, j) to the nearest obstacle cell of column i
    // (kFar: none); only where a frontier or ring cell needs it
    constexpr int32_t kFar = 1 << 28;
    std::vector<int32_t> colNear;
    if (reach >= 0) {
        colNear.resize(map.cells.size());
        const TFusedCell* c = cells;
        for (int i = 0; i < n; i++)
            colNear[size_t(i)] = c[i] == TFusedCell::Obstacle ? 0 : kFar;
        for (int j = 1; j < n; j++) {
            const size_t row = size_t(j) * n;
            for (int i = 0; i < n; i++)
                colNear[row + i] = c[row + i] == TFusedCell::Obstacle
                                       ? 0
                                       : std::min(colNear[row - n + i] + 1, kFar);
        }
        for (int j = n - 2; j >= 0; j--) {
            const size_t row = size_t(j) * n;
            for (int i = 0; i < n; i++)
                colNear[row + i] = std::min(colNear[row + i], colNear[row + n + i] + 1);
        }
    }
    auto nearObstacle = [&](int i, int j) {
        const size_t row = size_t(j) * n;
        for (int di = -reach; di <= reach; di++) {
            const int m = reachDj[size_t(di + reach)];
            if (m >= 0 && i + di >= 0 && i + di < n && colNear[row + i + di] <= m)
                return true;
        }
        return false;
    };
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const size_t k = map.index(i, j);
            const bool ring = (i == 0 || j == 0 || i == n - 1 || j == n - 1) &&
                              map.cells[k] == TFusedCell::Free;
            if (!wayOn[k] && !ring)
                continue;  // no way on, whatever its distance
            if (reach >= 0 && nearObstacle(i, j))
                wayOn[k] = 0;
            else if (ring)
                wayOn[k] = 1;
        }
    f.wayOnDist = distanceTo(wayOn, n, map.resolution, false);
    return f;
}
}  // namespace risknav::speed
