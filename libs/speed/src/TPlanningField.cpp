#include <risknav/speed/TPlanningField.h>

#include <risknav/mapping/distance_transform.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace risknav::speed {
using mapping::TFusedCell;

namespace {
/** sqrt(float(d2)) - 0.5 for the small squared distances, which are most
 * of a local map's (a speed-up: one look-up instead of a square root; the
 * same doubles, so the same floats). */
const std::vector<double>& halfCellLessRoots() {
    static const std::vector<double> table = [] {
        std::vector<double> t(4096);
        for (size_t d2 = 0; d2 < t.size(); d2++)
            t[d2] = double(std::sqrt(float(d2))) - 0.5;
        return t;
    }();
    return table;
}

/** The distance [m] a squared centre distance `d2` [cells^2] measures: to
 * the source cell's near edge (centre distance - half a cell: a robot disc
 * at a cell centre with radius below this does not touch it), the float
 * square root of the exact squared one (what OpenCV's precise transform,
 * used here before, gave); +inf for kNoSource. */
void toMetres(const std::vector<int32_t>& d2, double res, std::vector<float>& out) {
    out.resize(d2.size());
    const std::vector<double>& roots = halfCellLessRoots();
    const auto small = int32_t(roots.size());
    // runs of one value (0 on the unknown, none far from the frontier) are
    // most of a map: the last conversion is reused (a speed-up, same floats)
    int32_t last = mapping::kNoSource;
    float lastOut = std::numeric_limits<float>::infinity();
    for (size_t k = 0; k < d2.size(); k++) {
        if (d2[k] != last) {
            last = d2[k];
            const double root =
                last < small ? roots[size_t(last)] : double(std::sqrt(float(last))) - 0.5;
            lastOut = last == mapping::kNoSource ? std::numeric_limits<float>::infinity()
                                                 : float(std::max(0.0, root * res));
        }
        out[k] = lastOut;
    }
}
}  // namespace

double TPlanningField::clearanceAt(double x, double y) const {
    const int i = map.x2idx(x), j = map.y2idx(y);
    return map.inside(i, j) ? clearance[map.index(i, j)] : 0.0;
}

namespace {
/** The measured distances [m] (toMetres()) to `source`, exact for every cell
 * whose distance is <= `reach` [m]; the bounded transform where that saves
 * time, read through a table of the same floats toMetres() gives (a
 * speed-up: no pass over the squared distances). */
void distancesUpTo(const std::vector<uint8_t>& source, int n, bool borderIsSource,
                   double res, double reach, std::vector<float>& out) {
    // every cell whose measured distance is <= reach has a centre distance
    // <= reach / res + 0.5 cells (one more for rounding)
    const double reachCells = std::max(0.0, reach / res + 1.5);
    if (reachCells < std::min(n, 4096)) {
        const int r = int(std::ceil(reachCells));
        std::vector<int32_t> all(size_t(r) * r + 1);
        for (size_t k = 0; k < all.size(); k++)
            all[k] = int32_t(k);
        std::vector<float> metres;
        toMetres(all, res, metres);
        mapping::boundedDistanceTransform(source, n, n, borderIsSource, r, metres,
                                          std::numeric_limits<float>::infinity(), out);
        return;
    }
    std::vector<int32_t> d2;
    mapping::squaredDistanceTransform(source, n, n, borderIsSource, d2);
    toMetres(d2, res, out);
}

/** TPlanningField::clearance of `map`, exact up to `reach` [m]. */
void clearanceOf(const mapping::TFreeSpaceMap& map, double reach,
                 std::vector<float>& out) {
    std::vector<uint8_t> blocked(map.cells.size());
    const TFusedCell* cells = map.cells.data();
    // through local pointers: the loop vectorizes (a speed-up; the same)
    uint8_t* b = blocked.data();
    for (size_t k = 0, nk = map.cells.size(); k < nk; k++)
        b[k] = cells[k] != TFusedCell::Free;
    distancesUpTo(blocked, map.size, true, map.resolution, reach, out);
}

/** TPlanningField::wayOnDist of `map`, exact up to `wayOnReach` [m]. */
void wayOnDistOf(const mapping::TFreeSpaceMap& map, double minOpening, double wayOnReach,
                 std::vector<float>& out) {
    const int n = map.size;
    // wayOn: the frontier cells, then (below) only the open ones and the ring
    std::vector<uint8_t> wayOn(map.cells.size(), 0);
    const TFusedCell* cells = map.cells.data();
    auto frontierAt = [&](int i, int j) {
        const size_t k = map.index(i, j);
        auto freeAt = [&](size_t nk) { return cells[nk] == TFusedCell::Free; };
        return cells[k] == TFusedCell::Undecided &&
               ((i + 1 < n && freeAt(k + 1)) || (i > 0 && freeAt(k - 1)) ||
                (j + 1 < n && freeAt(k + size_t(n))) || (j > 0 && freeAt(k - size_t(n))));
    };
    // the inner cells without bounds checks or branches (a speed-up: the
    // loop vectorizes; the same cells)
    constexpr uint8_t kFree = uint8_t(TFusedCell::Free),
                      kUnd = uint8_t(TFusedCell::Undecided);
    const auto* raw = reinterpret_cast<const uint8_t*>(cells);
    for (int j = 0; j < n; j++) {
        uint8_t* w = &wayOn[size_t(j) * n];
        if (j == 0 || j == n - 1 || n < 3) {
            for (int i = 0; i < n; i++)
                w[i] = frontierAt(i, j);
            continue;
        }
        const uint8_t* r = raw + size_t(j) * n;
        const uint8_t *up = r - n, *down = r + n;
        w[0] = frontierAt(0, j);
        w[n - 1] = frontierAt(n - 1, j);
        for (int i = 1; i < n - 1; i++)
            w[i] = uint8_t((r[i] == kUnd) & ((r[i + 1] == kFree) | (r[i - 1] == kFree) |
                                             (up[i] == kFree) | (down[i] == kFree)));
    }
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
        // row by row through local pointers: the loops vectorize (a
        // speed-up; the same values)
        const auto* c = reinterpret_cast<const uint8_t*>(cells);
        constexpr uint8_t kObst = uint8_t(TFusedCell::Obstacle);
        int32_t* cn = colNear.data();
        for (int i = 0; i < n; i++)
            cn[i] = c[i] == kObst ? 0 : kFar;
        for (int j = 1; j < n; j++) {
            const uint8_t* cr = c + size_t(j) * n;
            const int32_t* up = cn + size_t(j - 1) * n;
            int32_t* o = cn + size_t(j) * n;
            for (int i = 0; i < n; i++)
                o[i] = cr[i] == kObst ? 0 : std::min(up[i] + 1, kFar);
        }
        for (int j = n - 2; j >= 0; j--) {
            const int32_t* down = cn + size_t(j + 1) * n;
            int32_t* o = cn + size_t(j) * n;
            for (int i = 0; i < n; i++)
                o[i] = std::min(o[i], down[i] + 1);
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
    for (int j = 0; j < n; j++) {
        const bool edgeRow = j == 0 || j == n - 1;
        for (int i = 0; i < n; i++) {
            const size_t k = map.index(i, j);
            if (!wayOn[k] && !(edgeRow || i == 0 || i == n - 1))
                continue;  // no way on, whatever its distance (most cells)
            const bool ring =
                (edgeRow || i == 0 || i == n - 1) && map.cells[k] == TFusedCell::Free;
            if (!wayOn[k] && !ring)
                continue;
            if (reach >= 0 && nearObstacle(i, j))
                wayOn[k] = 0;
            else if (ring)
                wayOn[k] = 1;
        }
    }
    distancesUpTo(wayOn, n, false, map.resolution, wayOnReach, out);
}
}  // namespace

const std::vector<float>& TPlanningField::wayOnDist() const {
    if (!m_wayOnReady) {
        wayOnDistOf(map, minOpening, wayOnReach, m_wayOnDist);
        m_wayOnReady = true;
    }
    return m_wayOnDist;
}

TPlanningField computePlanningField(const mapping::TFreeSpaceMap& map, double minOpening,
                                    double wayOnReach, double clearanceReach,
                                    const common::TParallelFor& parallel, bool wayOnNow) {
    TPlanningField f;
    f.map = map;
    f.wayOnReach = wayOnReach;
    f.clearanceReach = clearanceReach;
    f.minOpening = minOpening;
    // the two parts read only the map and each writes its own field
    common::parallelFor(wayOnNow ? parallel : common::TParallelFor{}, wayOnNow ? 2 : 1,
                        [&](size_t part) {
                            if (part == 0)
                                clearanceOf(map, clearanceReach, f.clearance);
                            else
                                (void)f.wayOnDist();
                        });
    return f;
}
}  // namespace risknav::speed
