#include <risknav/common/TGridSearchScratch.h>
#include <risknav/geometry/polyline.h>
#include <risknav/speed/IPathPlanner.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace risknav::speed {
namespace {
// (the local grid's A* state, reused per thread)
using TAStarScratch = common::TGridSearchScratch<std::pair<double, int32_t>>;
thread_local TAStarScratch t_astar;
}  // namespace

CTraversable::CTraversable(const TPlanningField& field, int si, int sj, double inflation,
                           bool escape)
    : m_field(field),
      m_si(si),
      m_sj(sj),
      m_inflation(inflation),
      m_startClear(field.clearance[field.map.index(si, sj)]),
      m_escapeRadius(inflation + 2 * field.map.resolution),
      m_escape(escape) {
    if (!m_escape || startKeepsInflation())
        return;
    // The escape first without rounding: never nearer than the start. Half a
    // cell of rounding per cycle would let a robot that starts each cycle a
    // little nearer creep, cycle by cycle, onto a door post; it is allowed
    // only when no strict way out exists.
    const auto& m = field.map;
    std::vector<uint8_t> seen(m.cells.size(), 0);
    std::vector<std::pair<int, int>> stack = {{si, sj}};
    seen[m.index(si, sj)] = 1;
    while (!stack.empty()) {
        const auto [i, j] = stack.back();
        stack.pop_back();
        if (field.clearance[m.index(i, j)] >= inflation)
            return;  // a strict way out exists
        for (int dj = -1; dj <= 1; dj++)
            for (int di = -1; di <= 1; di++) {
                const int ni = i + di, nj = j + dj;
                if (!m.inside(ni, nj) || seen[m.index(ni, nj)] || !(*this)(ni, nj))
                    continue;
                seen[m.index(ni, nj)] = 1;
                stack.emplace_back(ni, nj);
            }
    }
    m_slack = 0.5 * field.map.resolution;
}

bool CTraversable::operator()(int i, int j) const {
    const double c = m_field.clearance[m_field.map.index(i, j)];
    if (c >= m_inflation)
        return true;
    if (!(m_escape && c > 0 && c >= m_startClear - m_slack))
        return false;
    // libm's hypot only where the squared distance cannot decide (a speed-up)
    const double res = m_field.map.resolution, di = i - m_si, dj = j - m_sj;
    if ((di * di + dj * dj) * res * res > m_escapeRadius * m_escapeRadius * (1 + 1e-9))
        return false;
    return std::hypot(di, dj) * res <= m_escapeRadius;
}

TPlannedPath CGridPathPlanner::plan(const TPlanningField& field,
                                    const mrpt::math::TPoint2D& start,
                                    const mrpt::math::TPoint2D& goal, double inflation,
                                    double goalTolerance, bool escape,
                                    double maxCost) const {
    const auto& m = field.map;
    const int n = m.size;
    const double res = m.resolution;
    TPlannedPath out;
    const int si = m.x2idx(start.x), sj = m.y2idx(start.y);
    if (!m.inside(si, sj)) {
        out.points = {start};
        out.costToGo = std::hypot(goal.x - start.x, goal.y - start.y);
        return out;
    }
    const int gi = m.x2idx(goal.x), gj = m.y2idx(goal.y);
    const size_t s = m.index(si, sj);
    // a robot inside its own margin may leave with the clearance it has
    const CTraversable traversable(field, si, sj, inflation, escape);
    if (!traversable.startKeepsInflation() && !escape) {
        out.points = {start};
        return out;  // costToGo stays +inf
    }
    const double kDiag = std::sqrt(2.0);
    auto heuristic = [&](int i, int j) {
        const int dx = std::abs(i - gi), dy = std::abs(j - gj);
        // admissible for the goal region (a disc of goalTolerance)
        return std::max(0.0, (std::max(dx, dy) + (kDiag - 1) * std::min(dx, dy)) * res -
                                 goalTolerance);
    };
    TAStarScratch& a = t_astar;
    a.begin(size_t(n) * n);
    const uint32_t search = a.search;
    auto gOf = [&](size_t k) {
        return a.reached[k] == search ? a.g[k] : std::numeric_limits<float>::infinity();
    };
    // (f, cell) pairs are all distinct (a cell is pushed again only with a
    // lower g), so any exact min-heap pops the same sequence
    auto& open = a.open;
    a.g[s] = 0;
    a.parent[s] = -1;
    a.reached[s] = search;
    open.push({heuristic(si, sj), int32_t(s)});
    int32_t best = int32_t(s);
    double bestDist = std::hypot(m.idx2x(si) - goal.x, m.idx2y(sj) - goal.y);
    const bool goalInside = m.inside(gi, gj);
    bool found = false, cutOff = false;
    // f pops in non-decreasing order (a consistent heuristic): past this,
    // the destination's g, and so any path's cost-to-go, exceeds maxCost
    // (the path's ends are off the cell centres by < 1.5 cells in all, and
    // at a cell within the tolerance h is < 0.1 x the tolerance)
    const double fStop = maxCost + 2 * res + 0.1 * goalTolerance;
    while (!open.empty()) {
        const auto [f, k] = open.top();
        if (f > fStop) {
            cutOff = true;
            break;
        }
        open.pop();
        if (a.closed[size_t(k)] == search)
            continue;
        a.closed[size_t(k)] = search;
        const int i = k % n, j = k / n;
        // libm's hypot only where the squared distance cannot decide (a speed-up)
        const double gx = m.idx2x(i) - goal.x, gy = m.idx2y(j) - goal.y;
        const double decides = std::max(bestDist, goalTolerance);
        const bool mayCount = !(gx * gx + gy * gy > decides * decides * (1 + 1e-9));
        const double dGoal = mayCount ? std::hypot(gx, gy) : decides;
        if (mayCount && dGoal < bestDist - 1e-12) {
            bestDist = dGoal;
            best = k;
        }
        if ((goalInside && i == gi && j == gj) || (mayCount && dGoal <= goalTolerance)) {
            found = true;
            best = k;
            break;
        }
        for (int dj = -1; dj <= 1; dj++)
            for (int di = -1; di <= 1; di++) {
                if (!di && !dj)
                    continue;
                const int ni = i + di, nj = j + dj;
                if (!m.inside(ni, nj) || !traversable(ni, nj))
                    continue;
                const size_t nk = m.index(ni, nj);
                if (a.closed[nk] == search)
                    continue;
                const double ng = a.g[size_t(k)] + (di && dj ? kDiag : 1.0) * res;
                if (ng < gOf(nk)) {
                    a.g[nk] = float(ng);
                    a.parent[nk] = k;
                    a.reached[nk] = search;
                    open.push({ng + heuristic(ni, nj), int32_t(nk)});
                }
            }
    }
    std::vector<mrpt::math::TPoint2D> rev;
    for (int32_t k = best; k != int32_t(s) && k >= 0; k = a.parent[size_t(k)])
        rev.emplace_back(m.idx2x(k % n), m.idx2y(k / n));
    out.points.push_back(start);
    out.points.insert(out.points.end(), rev.rbegin(), rev.rend());
    if (found && goalInside && m.x2idx(out.points.back().x) == gi &&
        m.y2idx(out.points.back().y) == gj)
        out.points.back() = goal;
    for (size_t k = 1; k < out.points.size(); k++)
        out.length += std::hypot(out.points[k].x - out.points[k - 1].x,
                                 out.points[k].y - out.points[k - 1].y);
    out.reached =
        found || std::hypot(start.x - goal.x, start.y - goal.y) <= goalTolerance;
    // a start already within the tolerance is reached whatever the bound
    out.cutOff = cutOff && !out.reached;
    const auto& e = out.points.back();
    out.costToGo = out.reached ? out.length + std::hypot(e.x - goal.x, e.y - goal.y)
                               : std::numeric_limits<double>::infinity();
    return out;
}

double distanceToUndecided(const TPlannedPath& path, const TPlanningField& field,
                           double reach) {
    const auto& pts = path.points;
    double along = 0;
    for (size_t k = 0; k < pts.size(); k++) {
        if (k > 0)
            along += std::hypot(pts[k].x - pts[k - 1].x, pts[k].y - pts[k - 1].y);
        // the direction of travel here: towards a point a few cells on
        const size_t a = k + 1 < pts.size() ? k : (k > 0 ? k - 1 : k);
        const size_t b = std::min(pts.size() - 1, a + 3);
        if (a == b)
            break;
        const double h = std::atan2(pts[b].y - pts[a].y, pts[b].x - pts[a].x);
        for (const double off : {0.0, M_PI / 8, -M_PI / 8, M_PI / 4, -M_PI / 4}) {
            const double px = pts[k].x + reach * std::cos(h + off);
            const double py = pts[k].y + reach * std::sin(h + off);
            if (field.map.at(field.map.x2idx(px), field.map.y2idx(py)) ==
                mapping::TFusedCell::Undecided)
                return along;
        }
    }
    return std::numeric_limits<double>::infinity();
}

bool clearanceHoldsAhead(const TPlannedPath& path, const TPlanningField& field,
                         double inflation, double distance) {
    double along = 0;
    for (size_t k = 0; k < path.points.size(); k++) {
        if (k > 0)
            along += std::hypot(path.points[k].x - path.points[k - 1].x,
                                path.points[k].y - path.points[k - 1].y);
        if (along > distance)
            break;
        if (field.clearanceAt(path.points[k].x, path.points[k].y) < inflation)
            return false;
    }
    return true;
}
TLookahead lookaheadPoint(const TPlannedPath& path, const TPlanningField& field,
                          const mrpt::math::TPoint2D& p, double L) {
    return geometry::lookaheadOnPolyline(
        path.points, p, L, 0.5 * field.map.resolution,
        [&](double x, double y) { return field.clearanceAt(x, y); });
}
}  // namespace risknav::speed
