#include <risknav/common/CQuadHeap.h>
#include <risknav/common/TGridSearchScratch.h>
#include <risknav/planning/grid_search.h>

#include <algorithm>
#include <cmath>

namespace risknav::planning {
namespace {
/** An open entry: f, then h (of equal f the one nearer the goal first:
 * on a grid many paths tie, and without this A* opens all of them) */
struct TOpen {
    float f, h;
    int32_t cell;
    bool operator>(const TOpen& o) const { return f > o.f || (f == o.f && h > o.h); }
};
using TScratch = common::TGridSearchScratch<TOpen>;
thread_local TScratch t_scratch;
}  // namespace

TGridPath gridAStar(const TCostGrid& g, int32_t start, int32_t goal) {
    TGridPath out;
    const size_t n = size_t(g.w) * size_t(g.h);
    if (g.cost.size() != n || start < 0 || goal < 0 || size_t(start) >= n ||
        size_t(goal) >= n || !g.passable(size_t(start)) || !g.passable(size_t(goal)))
        return out;
    auto& s = t_scratch;
    s.begin(n);
    const int gx = goal % g.w, gy = goal / g.w;
    const float res = float(g.resolution);
    const float diag = float(std::sqrt(2.0)) * res;
    auto h = [&](int x, int y) {
        const int dx = std::abs(x - gx), dy = std::abs(y - gy);
        return res * float(std::max(dx, dy)) + (diag - res) * float(std::min(dx, dy));
    };
    s.g[size_t(start)] = 0;
    s.parent[size_t(start)] = -1;
    s.reached[size_t(start)] = s.search;
    {
        const float h0 = h(start % g.w, start / g.w);
        s.open.push({h0, h0, start});
    }
    static constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
    static constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    while (!s.open.empty()) {
        const int32_t c = s.open.top().cell;
        s.open.pop();
        if (s.closed[size_t(c)] == s.search)
            continue;  // a stale entry: the cell was closed at a lower f
        s.closed[size_t(c)] = s.search;
        out.expanded++;
        if (c == goal)
            break;
        const int cx = c % g.w, cy = c / g.w;
        const float gc = s.g[size_t(c)], cc = g.cost[size_t(c)];
        for (int k = 0; k < 8; k++) {
            const int nx = cx + kDx[k], ny = cy + kDy[k];
            if (!g.inside(nx, ny))
                continue;
            const size_t ni = g.index(nx, ny);
            if (!g.passable(ni) || s.closed[ni] == s.search)
                continue;
            if (k >= 4 && (!g.passable(g.index(nx, cy)) || !g.passable(g.index(cx, ny))))
                continue;
            const float step = k >= 4 ? diag : res;
            const float ng = gc + step * 0.5f * (cc + g.cost[ni]);
            if (s.reached[ni] == s.search && s.g[ni] <= ng)
                continue;
            s.reached[ni] = s.search;
            s.g[ni] = ng;
            s.parent[ni] = c;
            const float hn = h(nx, ny);
            s.open.push({ng + hn, hn, int32_t(ni)});
        }
    }
    if (s.closed[size_t(goal)] != s.search)
        return out;
    out.cost = s.g[size_t(goal)];
    for (int32_t c = goal; c >= 0; c = s.parent[size_t(c)])
        out.cells.push_back(c);
    std::reverse(out.cells.begin(), out.cells.end());
    return out;
}

double widestWayClearance(const std::vector<float>& clearance, int w, int h,
                          int32_t start, int32_t goal) {
    const size_t n = size_t(w) * size_t(h);
    if (clearance.size() != n || start < 0 || goal < 0 || size_t(start) >= n ||
        size_t(goal) >= n)
        return 0;
    // max-min Dijkstra: best[c] = the widest way's narrowest clearance to c
    std::vector<float> best(n, -1.0f);
    common::CQuadHeap<std::pair<float, int32_t>> open;  // largest first
    best[size_t(start)] = clearance[size_t(start)];
    open.emplace(best[size_t(start)], start);
    while (!open.empty()) {
        const auto [b, c] = open.top();
        open.pop();
        if (b < best[size_t(c)])
            continue;
        if (c == goal)
            return std::max(0.0f, b);
        if (!(b > 0))
            break;  // only cells of no clearance are left
        const int cx = c % w, cy = c / w;
        const int nx[4] = {cx + 1, cx - 1, cx, cx}, ny[4] = {cy, cy, cy + 1, cy - 1};
        for (int k = 0; k < 4; k++) {
            if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h)
                continue;
            const size_t ni = size_t(ny[k]) * size_t(w) + size_t(nx[k]);
            const float nb = std::min(b, clearance[ni]);
            if (nb > best[ni]) {
                best[ni] = nb;
                open.emplace(nb, int32_t(ni));
            }
        }
    }
    return 0;
}
}  // namespace risknav::planning
