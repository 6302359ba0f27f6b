#include <risknav/mapping/CFreeSpaceMemory.h>

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>

namespace risknav::mapping {
CFreeSpaceMemory::CFreeSpaceMemory(double size, double resolution, double cx, double cy)
    : m_n(0), m_res(resolution) {
    if (!(size > 0) || !(resolution > 0) || !(size / resolution <= 4096))
        throw std::invalid_argument(
            "CFreeSpaceMemory: size and resolution > 0, at most "
            "4096 cells a side");
    m_n = std::max(1, int(std::ceil(size / resolution)));
    m_xMin = cx - 0.5 * m_n * m_res;
    m_yMin = cy - 0.5 * m_n * m_res;
    m_cells.assign(size_t(m_n) * m_n, TState::Unknown);
}

int CFreeSpaceMemory::x2idx(double x) const {
    return int(std::floor((x - m_xMin) / m_res));
}
int CFreeSpaceMemory::y2idx(double y) const {
    return int(std::floor((y - m_yMin) / m_res));
}

CFreeSpaceMemory::TState CFreeSpaceMemory::at(double x, double y) const {
    const int i = x2idx(x), j = y2idx(y);
    if (i < 0 || j < 0 || i >= m_n || j >= m_n)
        return TState::Unknown;
    return m_cells[size_t(j) * m_n + i];
}

void CFreeSpaceMemory::update(const TFreeSpaceMap& local) {
    if (local.size <= 0)
        return;
    const double ext = local.size * local.resolution;
    const int i0 = std::max(0, x2idx(local.xMin)), j0 = std::max(0, y2idx(local.yMin));
    const int i1 = std::min(m_n - 1, x2idx(local.xMin + ext));
    const int j1 = std::min(m_n - 1, y2idx(local.yMin + ext));
    if (i1 < i0 || j1 < j0)
        return;
    const int w = i1 - i0 + 1, h = j1 - j0 + 1;
    std::vector<int> total(size_t(w) * h, 0), free(total.size(), 0),
        obst(total.size(), 0);
    // the memory column of each local column, once (not per cell)
    std::vector<int> column(size_t(local.size));
    for (int li = 0; li < local.size; li++)
        column[size_t(li)] = x2idx(local.idx2x(li)) - i0;
    for (int lj = 0; lj < local.size; lj++) {
        const int j = y2idx(local.idx2y(lj)) - j0;
        if (j < 0 || j >= h)
            continue;
        for (int li = 0; li < local.size; li++) {
            const int i = column[size_t(li)];
            if (i < 0 || i >= w)
                continue;
            const size_t k = size_t(j) * w + i;
            total[k]++;
            const TFusedCell c = local.cells[local.index(li, lj)];
            free[k] += c == TFusedCell::Free;
            obst[k] += c == TFusedCell::Obstacle;
        }
    }
    // fine cells per memory cell when fully covered
    const double perCell = (m_res / local.resolution) * (m_res / local.resolution);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const size_t k = size_t(j) * w + i;
            TState& s = m_cells[size_t(j + j0) * m_n + (i + i0)];
            if (obst[k] > 0)  // also on the window's edge: a wall just there
                s = TState::Obstacle;
            else if (total[k] >= 0.5 * perCell && 2 * free[k] >= total[k])
                s = TState::Free;
        }
}

void CFreeSpaceMemory::computeCostToGoal(const mrpt::math::TPoint2D& goal,
                                         double unknownWeight,
                                         const TFreeSpaceMap& window,
                                         double robotRadius) {
    m_goal = goal;
    m_weight = unknownWeight;
    const float inf = std::numeric_limits<float>::infinity();
    m_cost.assign(m_cells.size(), inf);
    const int gi = x2idx(goal.x), gj = y2idx(goal.y);
    using TEntry = std::pair<float, size_t>;
    std::priority_queue<TEntry, std::vector<TEntry>, std::greater<TEntry>> open;
    auto stepCost = [&](TState s) { return s == TState::Free ? 1.0 : unknownWeight; };
    // the local map's free cells are the local planner's part of the way
    const double wx0 = window.xMin, wy0 = window.yMin;
    const double wx1 = wx0 + window.size * window.resolution;
    const double wy1 = wy0 + window.size * window.resolution;
    // Obstacles grown by the robot's radius (a gap narrower than the robot,
    // e.g. an undecided cell or two in a seen wall, is no way on), except
    // around the goal itself
    const int grow = int(std::lround(robotRadius / m_res));
    std::vector<uint8_t> closed(m_cells.size(), 0);
    for (int j = 0; j < m_n; j++)
        for (int i = 0; i < m_n; i++) {
            if (m_cells[size_t(j) * m_n + i] != TState::Obstacle)
                continue;
            for (int nj = std::max(0, j - grow); nj <= std::min(m_n - 1, j + grow); nj++)
                for (int ni = std::max(0, i - grow); ni <= std::min(m_n - 1, i + grow);
                     ni++)
                    if (std::hypot(ni - gi, nj - gj) > grow + 1 ||
                        m_cells[size_t(nj) * m_n + ni] == TState::Obstacle)
                        closed[size_t(nj) * m_n + ni] = 1;
        }
    // ... and the local map's free cells
    for (int j = 0; j < m_n; j++) {
        const double y = m_yMin + (j + 0.5) * m_res;
        if (y < wy0 || y >= wy1)
            continue;
        const int lj = window.y2idx(y);
        for (int i = 0; i < m_n; i++) {
            const double x = m_xMin + (i + 0.5) * m_res;
            if (x >= wx0 && x < wx1 && window.at(window.x2idx(x), lj) == TFusedCell::Free)
                closed[size_t(j) * m_n + i] = 1;
        }
    }
    // Only the box around the window and the goal, 5 m beyond them: a way
    // on that leaves it by more is not worth ranking (and the search stays
    // a fraction of the memory)
    const double margin = 5.0;
    const int bi0 = std::max(0, x2idx(std::min(wx0, goal.x) - margin));
    const int bj0 = std::max(0, y2idx(std::min(wy0, goal.y) - margin));
    const int bi1 = std::min(m_n - 1, x2idx(std::max(wx1, goal.x) + margin));
    const int bj1 = std::min(m_n - 1, y2idx(std::max(wy1, goal.y) + margin));
    auto blocked = [&](int i, int j) {
        return i < bi0 || j < bj0 || i > bi1 || j > bj1 ||
               closed[size_t(j) * m_n + i] != 0;
    };

    if (gi >= 0 && gj >= 0 && gi < m_n && gj < m_n) {
        m_cost[size_t(gj) * m_n + gi] = 0;
        open.emplace(0.f, size_t(gj) * m_n + gi);
    } else {
        // a goal outside the memory: its border cells start with the
        // straight line to the goal
        for (int j = 0; j < m_n; j++)
            for (int i = 0; i < m_n; i++) {
                if (i != 0 && j != 0 && i != m_n - 1 && j != m_n - 1)
                    continue;
                const size_t k = size_t(j) * m_n + i;
                if (blocked(i, j))
                    continue;
                const float c = float(unknownWeight *
                                      std::hypot(m_xMin + (i + 0.5) * m_res - goal.x,
                                                 m_yMin + (j + 0.5) * m_res - goal.y));
                m_cost[k] = c;
                open.emplace(c, k);
            }
    }
    while (!open.empty()) {
        const auto [c, k] = open.top();
        open.pop();
        if (c > m_cost[k])
            continue;
        const int i = int(k % size_t(m_n)), j = int(k / size_t(m_n));
        for (int dj = -1; dj <= 1; dj++)
            for (int di = -1; di <= 1; di++) {
                const int ni = i + di, nj = j + dj;
                if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= m_n || nj >= m_n ||
                    blocked(ni, nj))
                    continue;
                if (di != 0 && dj != 0 && (blocked(i + di, j) || blocked(i, j + dj)))
                    continue;
                const size_t nk = size_t(nj) * m_n + ni;
                // half the step in each cell's own cost
                const double len = (di != 0 && dj != 0 ? M_SQRT2 : 1.0) * m_res;
                const float nc =
                    float(c + 0.5 * len * (stepCost(m_cells[k]) + stepCost(m_cells[nk])));
                if (nc < m_cost[nk]) {
                    m_cost[nk] = nc;
                    open.emplace(nc, nk);
                }
            }
    }
}

double CFreeSpaceMemory::costToGoal(double x, double y, double reach) const {
    const int i = x2idx(x), j = y2idx(y);
    if (m_cost.empty() || i < 0 || j < 0 || i >= m_n || j >= m_n)
        return m_weight * std::hypot(x - m_goal.x, y - m_goal.y);
    const int r = int(std::ceil(reach / m_res));
    double c = std::numeric_limits<double>::infinity();
    for (int nj = std::max(0, j - r); nj <= std::min(m_n - 1, j + r); nj++)
        for (int ni = std::max(0, i - r); ni <= std::min(m_n - 1, i + r); ni++) {
            const double d = std::hypot(m_xMin + (ni + 0.5) * m_res - x,
                                        m_yMin + (nj + 0.5) * m_res - y);
            if (d <= reach + 0.75 * m_res)
                c = std::min(c, m_cost[size_t(nj) * m_n + ni] + d);
        }
    return c;
}
}  // namespace risknav::mapping
