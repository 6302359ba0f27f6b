#include <risknav/common/config_read.h>
#include <risknav/geometry/graph.h>
#include <risknav/geometry/homotopy.h>
#include <risknav/geometry/polyline.h>
#include <risknav/risk/CGvgRoutes.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>

using mrpt::math::TPoint2D;
using risknav::geometry::TGraphEdge;

namespace risknav::risk {
namespace {
// Zhang & Suen (1984) thinning of a 0/1 mask, in place.
void thin(std::vector<uint8_t>& m, int w, int h) {
    auto at = [&](int x, int y) -> int {
        return (x >= 0 && y >= 0 && x < w && y < h) ? m[size_t(y) * w + x] : 0;
    };
    std::vector<size_t> del;
    bool changed = true;
    while (changed) {
        changed = false;
        for (int pass = 0; pass < 2; pass++) {
            del.clear();
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    if (!m[size_t(y) * w + x])
                        continue;
                    // Neighbours P2..P9, clockwise from north (y grows "north" here;
                    // symmetric anyway).
                    const int p[8] = {
                        at(x, y + 1), at(x + 1, y + 1), at(x + 1, y), at(x + 1, y - 1),
                        at(x, y - 1), at(x - 1, y - 1), at(x - 1, y), at(x - 1, y + 1)};
                    const int b = std::accumulate(p, p + 8, 0);
                    if (b < 2 || b > 6)
                        continue;
                    int a = 0;
                    for (int i = 0; i < 8; i++)
                        a += (p[i] == 0 && p[(i + 1) % 8] == 1);
                    if (a != 1)
                        continue;
                    if (pass == 0 && (p[0] * p[2] * p[4] != 0 || p[2] * p[4] * p[6] != 0))
                        continue;
                    if (pass == 1 && (p[0] * p[2] * p[6] != 0 || p[0] * p[4] * p[6] != 0))
                        continue;
                    del.push_back(size_t(y) * w + x);
                }
            for (size_t i : del)
                m[i] = 0;
            changed |= !del.empty();
        }
    }
}
}  // namespace

void CGvgRoutes::TOptions::declare(Visitor& v) {
    v.number(separation_ratio, "gvg_separation_ratio", common::TRange::closed(0.1, 2),
             "GVG cell test: nearest obstacle cells of neighbours >= ratio x clearance "
             "apart");
    v.number(simplify_tolerance, "gvg_simplify_tolerance",
             common::TRange::closed(0, 2, "m"),
             "Douglas-Peucker tolerance of GVG routes");
}

CGvgRoutes::CGvgRoutes(const CObstacleField& f, const TOptions& o)
    : m_field(f), m_opts(o) {
    o.validate();
    const int w = f.sizeX(), h = f.sizeY();
    const double res = f.resolution();
    const double minClear = f.robotRadius();
    const auto& raw = f.distanceField().obstacles();
    auto isFree = [&](int x, int y) { return !raw[size_t(y) * w + x]; };
    const mapping::TNearestObstacles near = f.distanceField().nearestObstacles();
    m_skel.assign(size_t(w) * h, 0);
    if (!near.any)
        return;  // no obstacle at all: no GVG
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if (!isFree(x, y))
                continue;
            const size_t p = near.index(x, y);
            const float d = near.distCells[p];
            if (d * res < minClear)
                continue;
            const double need = std::max(2.0, o.separation_ratio * d);
            const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (const auto& n : nb) {
                const int qx = x + n[0], qy = y + n[1];
                if (qx < 0 || qy < 0 || qx >= w || qy >= h || !isFree(qx, qy))
                    continue;
                const size_t q = near.index(qx, qy);
                if (std::hypot(near.obstX[p] - near.obstX[q],
                               near.obstY[p] - near.obstY[q]) >= need) {
                    m_skel[size_t(y) * w + x] = 1;
                    break;
                }
            }
        }
    thin(m_skel, w, h);
    bridgeGaps(near);
    for (size_t i = 0; i < m_skel.size(); i++)
        if (m_skel[i])
            m_pixels.push_back(uint32_t(i));
}

void CGvgRoutes::bridgeGaps(const mapping::TNearestObstacles& near) {
    // Where a corridor opens into a room the separation test leaves the
    // medial lines a little apart. Join every skeleton end to the nearest
    // skeleton pixel within 2.5 x its clearance that is far from it ALONG the
    // skeleton (more than 3 x the straight distance, or not reachable at all),
    // by a straight obstacle-free line: a bridge that makes a new way, not a
    // shortcut along the same branch.
    const int w = m_field.sizeX(), h = m_field.sizeY();
    auto on = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h && m_skel[size_t(y) * w + x];
    };
    std::vector<std::pair<int, int>> ends;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if (!on(x, y))
                continue;
            int deg = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    deg += (dx || dy) && on(x + dx, y + dy);
            if (deg <= 1)
                ends.emplace_back(x, y);
        }
    for (const auto& [ex, ey] : ends) {
        const double reach = std::max(3.0, 2.5 * near.distCells[near.index(ex, ey)]);
        const int r = int(std::ceil(reach));
        // Geodesic distances (in 8-connected steps) from the end, bounded.
        std::map<size_t, int> geo;
        std::vector<std::pair<int, int>> frontier = {{ex, ey}};
        geo[size_t(ey) * w + ex] = 0;
        const int limit = int(4 * reach) + 4;
        for (int depth = 1; depth <= limit && !frontier.empty(); depth++) {
            std::vector<std::pair<int, int>> next;
            for (const auto& [x, y] : frontier)
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++)
                        if ((dx || dy) && on(x + dx, y + dy) &&
                            !geo.count(size_t(y + dy) * w + x + dx)) {
                            geo[size_t(y + dy) * w + x + dx] = depth;
                            next.emplace_back(x + dx, y + dy);
                        }
            frontier.swap(next);
        }
        double bestD = reach + 1;
        int bx = -1, by = -1;
        for (int qy = std::max(0, ey - r); qy <= std::min(h - 1, ey + r); qy++)
            for (int qx = std::max(0, ex - r); qx <= std::min(w - 1, ex + r); qx++) {
                if (!on(qx, qy))
                    continue;
                const double d = std::hypot(qx - ex, qy - ey);
                if (d >= bestD)
                    continue;
                const auto g = geo.find(size_t(qy) * w + qx);
                if (g != geo.end() && g->second <= 3 * d + 2)
                    continue;
                if (!m_field.segmentFree(m_field.colToX(ex), m_field.rowToY(ey),
                                         m_field.colToX(qx), m_field.rowToY(qy)))
                    continue;
                bestD = d;
                bx = qx;
                by = qy;
            }
        if (bx < 0)
            continue;
        const int n = int(std::ceil(bestD));
        for (int k = 0; k <= n; k++)
            m_skel[size_t(std::lround(ey + double(by - ey) * k / n)) * w +
                   size_t(std::lround(ex + double(bx - ex) * k / n))] = 1;
    }
}

long CGvgRoutes::attach(const TPoint2D& p) const {
    const int w = m_field.sizeX();
    std::vector<std::pair<double, uint32_t>> byDist;
    for (uint32_t i : m_pixels)
        byDist.emplace_back(std::hypot(m_field.colToX(int(i % w)) - p.x,
                                       m_field.rowToY(int(i / w)) - p.y),
                            i);
    std::sort(byDist.begin(), byDist.end());
    for (const auto& [d, i] : byDist)
        if (m_field.segmentFree(p.x, p.y, m_field.colToX(int(i % w)),
                                m_field.rowToY(int(i / w))))
            return long(i);
    return -1;
}

std::vector<TPoint2D> CGvgRoutes::simplify(const std::vector<TPoint2D>& pts) const {
    return geometry::simplifyDouglasPeucker(
        pts, m_opts.simplify_tolerance, [this](const TPoint2D& a, const TPoint2D& b) {
            return m_field.segmentFree(a.x, a.y, b.x, b.y);
        });
}

std::vector<std::vector<TPoint2D>> CGvgRoutes::routes(const TPoint2D& start,
                                                      const TPoint2D& goal,
                                                      size_t k) const {
    std::vector<std::vector<TPoint2D>> out;
    const long sa = attach(start), ga = attach(goal);
    if (sa < 0 || ga < 0 || k == 0)
        return out;
    const int w = m_field.sizeX(), h = m_field.sizeY();
    auto isSkel = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h && m_skel[size_t(y) * w + x];
    };
    auto neighbours = [&](uint32_t i) {
        std::vector<uint32_t> n;
        const int x = int(i % w), y = int(i / w);
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++)
                if ((dx || dy) && isSkel(x + dx, y + dy))
                    n.push_back(uint32_t((y + dy) * w + x + dx));
        return n;
    };
    // Special pixels (junctions, ends, the two attachment points), merged into
    // clusters when adjacent: the graph's nodes.
    std::map<uint32_t, size_t> cluster;
    std::vector<uint32_t> specials;
    for (uint32_t i : m_pixels)
        if (neighbours(i).size() != 2 || long(i) == sa || long(i) == ga)
            specials.push_back(i);
    std::vector<size_t> parent(specials.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<size_t(size_t)> find = [&](size_t a) {
        return parent[a] == a ? a : parent[a] = find(parent[a]);
    };
    std::map<uint32_t, size_t> specIdx;
    for (size_t s = 0; s < specials.size(); s++)
        specIdx[specials[s]] = s;
    for (size_t s = 0; s < specials.size(); s++)
        for (uint32_t n : neighbours(specials[s]))
            if (specIdx.count(n))
                parent[find(s)] = find(specIdx[n]);
    std::map<size_t, size_t> rootToNode;
    for (size_t s = 0; s < specials.size(); s++) {
        const size_t r = find(s);
        if (!rootToNode.count(r))
            rootToNode[r] = rootToNode.size();
        cluster[specials[s]] = rootToNode[r];
    }
    // Branches between clusters: the edges, with their pixel chains.
    std::vector<TGraphEdge> edges;
    std::vector<std::vector<uint32_t>> chains;
    std::vector<uint8_t> visited(m_skel.size(), 0);
    auto pixelLen = [&](uint32_t a, uint32_t b) {
        return std::hypot(int(a % w) - int(b % w), int(a / w) - int(b / w)) *
               m_field.resolution();
    };
    for (uint32_t s : specials)
        for (uint32_t n : neighbours(s)) {
            if (cluster.count(n)) {
                if (cluster[n] != cluster[s] && s < n) {
                    edges.push_back({cluster[s], cluster[n], pixelLen(s, n)});
                    chains.push_back({s, n});
                }
                continue;
            }
            if (visited[n])
                continue;
            std::vector<uint32_t> chain = {s, n};
            visited[n] = 1;
            uint32_t prev = s, cur = n;
            double len = pixelLen(s, n);
            bool ok = true;
            while (!cluster.count(cur)) {
                uint32_t next = UINT32_MAX;
                for (uint32_t q : neighbours(cur))
                    if (q != prev && (cluster.count(q) || !visited[q])) {
                        next = q;
                        break;
                    }
                if (next == UINT32_MAX) {
                    ok = false;  // a dead loop back into visited pixels
                    break;
                }
                if (!cluster.count(next))
                    visited[next] = 1;
                len += pixelLen(cur, next);
                chain.push_back(next);
                prev = cur;
                cur = next;
            }
            if (!ok || cluster[cur] == cluster[s])
                continue;
            edges.push_back({cluster[s], cluster[cur], len});
            chains.push_back(chain);
        }
    const size_t src = cluster[uint32_t(sa)], dst = cluster[uint32_t(ga)];
    auto px = [&](uint32_t i) {
        return TPoint2D(m_field.colToX(int(i % w)), m_field.rowToY(int(i / w)));
    };
    if (src == dst) {
        out.push_back(simplify({start, px(uint32_t(sa)), px(uint32_t(ga)), goal}));
        return out;
    }
    for (const auto& p : geometry::kShortestPaths(rootToNode.size(), edges, src, dst,
                                                  std::min<size_t>(8 * k, 200))) {
        std::vector<TPoint2D> pts = {start, px(uint32_t(sa))};
        for (size_t e = 0; e < p.edges.size(); e++) {
            const auto& ch = chains[p.edges[e]];
            const bool forward = edges[p.edges[e]].a == p.nodes[e];
            for (size_t q = 0; q < ch.size(); q++)
                pts.push_back(px(forward ? ch[q] : ch[ch.size() - 1 - q]));
        }
        pts.push_back(px(uint32_t(ga)));
        pts.push_back(goal);
        // Drop repeated points (chains share their end pixels).
        std::vector<TPoint2D> u;
        for (const auto& q : pts)
            if (u.empty() || std::hypot(q.x - u.back().x, q.y - u.back().y) > 1e-9)
                u.push_back(q);
        const bool variant =
            std::any_of(out.begin(), out.end(),
                        [&](const std::vector<TPoint2D>& o) { return sameWay(o, u); });
        if (variant)
            continue;
        out.push_back(simplify(u));
        if (out.size() >= k)
            break;
    }
    return out;
}

bool CGvgRoutes::sameWay(const std::vector<TPoint2D>& a,
                         const std::vector<TPoint2D>& b) const {
    // The RAW obstacles (not grown by the robot radius): a route may pass
    // close to an obstacle, only one enclosed between the routes counts.
    geometry::TObstacleRaster r;
    r.sizeX = m_field.sizeX();
    r.sizeY = m_field.sizeY();
    r.xMin = m_field.xMin();
    r.yMin = m_field.yMin();
    r.resolution = m_field.resolution();
    const auto& raw = m_field.distanceField().obstacles();
    r.isObstacle = [&raw, w = r.sizeX](int cx, int cy) {
        return raw[size_t(cy) * w + cx] != 0;
    };
    return geometry::sameHomotopy(a, b, r);
}

}  // namespace risknav::risk
