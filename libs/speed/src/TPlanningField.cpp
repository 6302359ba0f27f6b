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
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            if (map.cells[map.index(i, j)] != TFusedCell::Undecided)
                continue;
            const int di[] = {1, -1, 0, 0}, dj[] = {0, 0, 1, -1};
            for (int k = 0; k < 4; k++)
                if (map.inside(i + di[k], j + dj[k]) &&
                    map.cells[map.index(i + di[k], j + dj[k])] == TFusedCell::Free) {
                    wayOn[map.index(i, j)] = 1;
                    break;
                }
        }
    f.clearance = distanceTo(blocked, n, map.resolution, true);
    // The ways on, for the choice of a temporary destination: open frontier
    // cells, and the grid's outer ring, whose free cells lead on into what the
    // robot-centred grid no longer (or not yet) holds
    // "Nearer than minOpening to an obstacle cell", measured as distanceTo()
    // measures (centre to near edge, sqrtf of the exact squared centre
    // distance) but only where it decides something (frontier and ring
    // cells): the cell offsets whose squared distance gives less than
    // minOpening, searched for an obstacle (a speed-up of the full distance
    // transform this took; the same cells pass, as the distance is monotone)
    std::vector<std::pair<int, int>> near;
    if (minOpening > 0) {
        const double res = map.resolution;
        auto measured = [&](int d2) {
            return float(std::max(0.0, (double(std::sqrt(float(d2))) - 0.5) * res));
        };
        const int reach = int(std::ceil(minOpening / res + 1.5));
        for (int dj = -reach; dj <= reach; dj++)
            for (int di = -reach; di <= reach; di++)
                if (measured(di * di + dj * dj) < minOpening)
                    near.emplace_back(di, dj);
        // nearest first: most frontier cells along a wall end at the first
        std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) {
            return a.first * a.first + a.second * a.second <
                   b.first * b.first + b.second * b.second;
        });
    }
    auto nearObstacle = [&](int i, int j) {
        for (const auto& [di, dj] : near)
            if (map.inside(i + di, j + dj) &&
                map.cells[map.index(i + di, j + dj)] == TFusedCell::Obstacle)
                return true;
        return false;
    };
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const size_t k = map.index(i, j);
            const bool ring = (i == 0 || j == 0 || i == n - 1 || j == n - 1) &&
                              map.cells[k] == TFusedCell::Free;
            if (!wayOn[k] && !ring)
                continue;  // no way on, whatever its distance
            if (minOpening > 0 && nearObstacle(i, j))
                wayOn[k] = 0;
            else if (ring)
                wayOn[k] = 1;
        }
    f.wayOnDist = distanceTo(wayOn, n, map.resolution, false);
    return f;
}
}  // namespace risknav::speed
