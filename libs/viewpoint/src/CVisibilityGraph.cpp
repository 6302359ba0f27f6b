#include <risknav/viewpoint/CVisibilityGraph.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using mrpt::math::TPoint2D;

namespace risknav::viewpoint {
namespace {
// Tolerance of the exact clearance tests: the circumscribed corner polygon's
// edges are at exactly D_s from their corner, in floating point a few ulps
// either way.
constexpr double kEps = 1e-9;

double cross(const TPoint2D& a, const TPoint2D& b) {
    return a.x * b.y - a.y * b.x;
}
TPoint2D unit(double a) {
    return {std::cos(a), std::sin(a)};
}
TPoint2D rot90(const TPoint2D& v) {
    return {-v.y, v.x};
}
}  // namespace

CVisibilityGraph::CVisibilityGraph(const TPolygonWorld& world,
                                   const geometry::CSegmentIndex& index, double d,
                                   int segmentsPerCircle, const TPoint2D& start,
                                   const TPoint2D& goal)
    : m_world(world), m_index(index), m_d(d) {
    if (!(d > 0) || segmentsPerCircle < 4)
        throw std::invalid_argument("CVisibilityGraph: clearance > 0, segments >= 4");
    const double step = 2 * M_PI / segmentsPerCircle;
    // Corner nodes: the circumscribed polygon of the arc around each convex
    // corner (obstacle on the left of every ring: convex = left turn).
    for (const auto& r : world.rings()) {
        const size_t n = r.size();
        for (size_t i = 0; i < n; i++) {
            const TPoint2D& p0 = r[(i + n - 1) % n];
            const TPoint2D& v = r[i];
            const TPoint2D& p1 = r[(i + 1) % n];
            const TPoint2D ein{v.x - p0.x, v.y - p0.y}, eout{p1.x - v.x, p1.y - v.y};
            if (cross(ein, eout) <= 0)
                continue;  // reflex or straight: no node
            // Outward normals (right of the edge direction).
            const double aIn = std::atan2(-ein.x, ein.y);
            const double aOut = std::atan2(-eout.x, eout.y);
            double ext = aOut - aIn;  // exterior angle in (0, pi)
            while (ext <= 0)
                ext += 2 * M_PI;
            while (ext > M_PI)
                ext -= 2 * M_PI;
            if (!(ext > 0))
                continue;
            const int nc = std::max(1, int(std::ceil(ext / step - 1e-12)));
            const double g = ext / nc;
            const double rr = d / std::cos(g / 2);
            for (int j = 0; j < nc; j++) {
                const double a = aIn + (j + 0.5) * g;
                TNode node;
                node.p = {v.x + rr * std::cos(a), v.y + rr * std::sin(a)};
                node.tin = rot90(unit(a - g / 2));
                node.tout = rot90(unit(a + g / 2));
                node.centre = v;
                if (pointFree(node.p))
                    m_nodes.push_back(node);
            }
        }
    }
    const size_t nCorner = m_nodes.size();
    m_start = m_nodes.size();
    m_nodes.push_back({start, {}, {}, start, false});
    m_goal = m_nodes.size();
    m_nodes.push_back({goal, {}, {}, goal, false});
    m_startFree = pointFree(start);
    m_goalFree = pointFree(goal);
    if (!m_startFree || !m_goalFree)
        return;
    auto add = [&](size_t i, size_t j) {
        const TPoint2D& a = m_nodes[i].p;
        const TPoint2D& b = m_nodes[j].p;
        const TPoint2D ab{b.x - a.x, b.y - a.y};
        if (!supports(i, ab) || !supports(j, {-ab.x, -ab.y}))
            return;
        if (!segmentFree(a, b))
            return;
        const double L = std::hypot(ab.x, ab.y);
        m_edges.push_back({i, j, L});
        // Directed tangent-graph edges, each way: node k in state s is split
        // node 2k + s, s = 0 when the obstacle is on the path's left.
        auto state = [&](size_t k, const TPoint2D& dir) -> size_t {
            const TNode& n = m_nodes[k];
            if (!n.corner)
                return 2 * k;
            return 2 * k +
                   (cross(dir, {n.centre.x - n.p.x, n.centre.y - n.p.y}) > 0 ? 0 : 1);
        };
        const TPoint2D ba{-ab.x, -ab.y};
        m_directed.push_back({state(i, ab), state(j, ab), L, true});
        m_directed.push_back({state(j, ba), state(i, ba), L, true});
    };
    for (size_t i = 0; i < nCorner; i++)
        for (size_t j = i + 1; j < nCorner; j++)
            add(i, j);
    for (size_t i = 0; i < nCorner; i++) {
        add(m_start, i);
        add(m_goal, i);
    }
    add(m_start, m_goal);
}

bool CVisibilityGraph::pointFree(const TPoint2D& p) const {
    return !m_world.insideObstacle(p) && m_index.distance(p, m_d) >= m_d - kEps;
}

bool CVisibilityGraph::segmentFree(const TPoint2D& a, const TPoint2D& b) const {
    return !m_index.anyWithin(a, b, m_d - kEps);
}

bool CVisibilityGraph::supports(size_t i, const TPoint2D& dir) const {
    const TNode& n = m_nodes[i];
    if (!n.corner)
        return true;
    // Both boundary neighbours on the same side of the line (or on it).
    const double c1 = cross(dir, {-n.tin.x, -n.tin.y});
    const double c2 = cross(dir, n.tout);
    const double tol = 1e-12 * std::hypot(dir.x, dir.y);
    return (c1 >= -tol && c2 >= -tol) || (c1 <= tol && c2 <= tol);
}

std::vector<TPoint2D> CVisibilityGraph::canonicalPolyline(
    const std::vector<size_t>& nodes) const {
    std::vector<TPoint2D> p;
    for (size_t v : nodes) {
        const TPoint2D& q = m_nodes[v].p;
        if (!p.empty() && std::hypot(q.x - p.back().x, q.y - p.back().y) <= 1e-9)
            continue;  // coincident nodes of touching C-obstacles
        // A point that only continues a straight line is no vertex.
        if (p.size() >= 2) {
            const TPoint2D& a = p[p.size() - 2];
            const TPoint2D& b = p.back();
            const TPoint2D u{b.x - a.x, b.y - a.y}, w{q.x - b.x, q.y - b.y};
            if (std::abs(cross(u, w)) <=
                    1e-12 * std::hypot(u.x, u.y) * std::hypot(w.x, w.y) &&
                u.x * w.x + u.y * w.y > 0)
                p.pop_back();
        }
        p.push_back(q);
    }
    return p;
}

bool CVisibilityGraph::taut(const std::vector<size_t>& split) const {
    // At a corner passed with the obstacle on the left (state 0) the path
    // turns left, on the right it turns right (or goes straight on): it
    // wraps the obstacle. Both edges being tangent on the same side is not
    // enough: two supporting lines of one corner can also make a kink away
    // from it.
    for (size_t i = 1; i + 1 < split.size(); i++) {
        const TPoint2D& a = m_nodes[split[i - 1] / 2].p;
        const TPoint2D& b = m_nodes[split[i] / 2].p;
        const TPoint2D& c = m_nodes[split[i + 1] / 2].p;
        const TPoint2D ein{b.x - a.x, b.y - a.y}, eout{c.x - b.x, c.y - b.y};
        const double turn = cross(ein, eout);
        const double tol = 1e-12 * std::hypot(ein.x, ein.y) * std::hypot(eout.x, eout.y);
        if (split[i] % 2 == 0 ? turn < -tol : turn > tol)
            return false;
    }
    return true;
}

std::vector<std::vector<TPoint2D>> CVisibilityGraph::kShortestPaths(size_t k) const {
    std::vector<std::vector<TPoint2D>> out;
    if (!m_startFree || !m_goalFree)
        return out;
    // Paths that pass a corner both ways round, or bend away from the
    // obstacle they are said to wrap, are dropped: ask Yen for a few more
    // than k, and for twice as many again while too many were dropped and
    // more exist.
    // A*: the straight-line distance to the goal bounds every split node's.
    std::vector<double> h(2 * m_nodes.size());
    const TPoint2D& g = m_nodes[m_goal].p;
    for (size_t v = 0; v < h.size(); v++)
        h[v] = std::hypot(m_nodes[v / 2].p.x - g.x, m_nodes[v / 2].p.y - g.y);
    for (size_t want = 2 * k + 4;; want *= 2) {
        out.clear();
        const auto paths = geometry::kShortestPaths(2 * m_nodes.size(), m_directed,
                                                    2 * m_start, 2 * m_goal, want, h);
        for (const auto& p : paths) {
            std::vector<size_t> phys;
            for (size_t v : p.nodes)
                phys.push_back(v / 2);
            std::vector<size_t> sorted = phys;
            std::sort(sorted.begin(), sorted.end());
            if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
                continue;
            if (!taut(p.nodes))
                continue;
            // The same route again (coincident nodes of overlapping
            // obstacles, points on a straight line): dropped.
            std::vector<TPoint2D> poly = canonicalPolyline(phys);
            const bool seen =
                std::any_of(out.begin(), out.end(), [&](const std::vector<TPoint2D>& q) {
                    return q.size() == poly.size() &&
                           std::equal(q.begin(), q.end(), poly.begin(),
                                      [](const TPoint2D& a, const TPoint2D& b) {
                                          return std::abs(a.x - b.x) <= 1e-9 &&
                                                 std::abs(a.y - b.y) <= 1e-9;
                                      });
                });
            if (seen)
                continue;
            out.push_back(std::move(poly));
            if (out.size() == k)
                break;
        }
        if (out.size() == k || paths.size() < want || want > 16 * (k + 4))
            break;
    }
    return out;
}

}  // namespace risknav::viewpoint
