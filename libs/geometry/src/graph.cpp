#include <risknav/geometry/graph.h>

#include <algorithm>
#include <limits>
#include <queue>
#include <set>
#include <tuple>

namespace risknav::geometry {
namespace {
using TAdjacency = std::vector<std::vector<size_t>>;  // node -> incident edge ids

TAdjacency adjacency(size_t n, const std::vector<TGraphEdge>& edges) {
    TAdjacency adj(n);
    for (size_t e = 0; e < edges.size(); e++) {
        adj[edges[e].a].push_back(e);
        if (edges[e].b != edges[e].a && !edges[e].directed)
            adj[edges[e].b].push_back(e);
    }
    return adj;
}

// Dijkstra over a prebuilt adjacency (Yen's spur searches reuse one); A*
// when a heuristic h (a consistent lower bound of the distance to target) is
// given: the queue is ordered by dist + h, the paths found are the same
// lengths.
TGraphPath dijkstra(const TAdjacency& adj, const std::vector<TGraphEdge>& edges,
                    size_t source, size_t target, const std::vector<bool>& edgeRemoved,
                    const std::vector<bool>& nodeRemoved,
                    const std::vector<double>& h = {}) {
    const size_t n = adj.size();
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> dist(n, inf);
    std::vector<size_t> viaEdge(n, size_t(-1));
    // (dist + h, dist, node): dist kept as pushed (recomputing it as f - h
    // would round and make a fresh entry look stale).
    using Q = std::tuple<double, double, size_t>;
    std::priority_queue<Q, std::vector<Q>, std::greater<Q>> pq;
    TGraphPath p;
    if (nodeRemoved[source] || nodeRemoved[target])
        return p;
    auto hOf = [&](size_t v) { return h.empty() ? 0.0 : h[v]; };
    dist[source] = 0;
    pq.push({hOf(source), 0.0, source});
    while (!pq.empty()) {
        const auto [f, d, u] = pq.top();
        pq.pop();
        if (d > dist[u])
            continue;
        if (u == target)
            break;
        for (size_t e : adj[u]) {
            if (edgeRemoved[e])
                continue;
            const size_t v = edges[e].a == u ? edges[e].b : edges[e].a;
            if (nodeRemoved[v])
                continue;
            const double nd = dist[u] + edges[e].length;
            if (nd < dist[v]) {
                dist[v] = nd;
                viaEdge[v] = e;
                pq.push({nd + hOf(v), nd, v});
            }
        }
    }
    if (dist[target] == inf)
        return p;
    for (size_t v = target; v != source;) {
        const size_t e = viaEdge[v];
        p.edges.push_back(e);
        p.nodes.push_back(v);
        v = edges[e].a == v ? edges[e].b : edges[e].a;
    }
    p.nodes.push_back(source);
    std::reverse(p.edges.begin(), p.edges.end());
    std::reverse(p.nodes.begin(), p.nodes.end());
    p.length = dist[target];
    return p;
}
}  // namespace

TGraphPath shortestPath(size_t n, const std::vector<TGraphEdge>& edges, size_t source,
                        size_t target, const std::vector<bool>& edgeRemoved,
                        const std::vector<bool>& nodeRemoved) {
    return dijkstra(adjacency(n, edges), edges, source, target, edgeRemoved, nodeRemoved);
}

TGraphPath shortestPath(size_t n, const std::vector<TGraphEdge>& edges, size_t source,
                        size_t target) {
    return shortestPath(n, edges, source, target, std::vector<bool>(edges.size(), false),
                        std::vector<bool>(n, false));
}

std::vector<TGraphPath> kShortestPaths(size_t n, const std::vector<TGraphEdge>& edges,
                                       size_t source, size_t target, size_t k,
                                       const std::vector<double>& heuristic) {
    std::vector<TGraphPath> A;
    std::vector<bool> noEdge(edges.size(), false), noNode(n, false);
    const TAdjacency adj = adjacency(n, edges);  // built once for every spur search
    TGraphPath first = dijkstra(adj, edges, source, target, noEdge, noNode, heuristic);
    if (first.nodes.empty() || k == 0)
        return A;
    A.push_back(first);
    // Candidates ordered by (length, edge list) for determinism.
    auto less = [](const TGraphPath& x, const TGraphPath& y) {
        return x.length != y.length ? x.length < y.length : x.edges < y.edges;
    };
    std::set<TGraphPath, decltype(less)> B(less);
    while (A.size() < k) {
        const TGraphPath& last = A.back();
        for (size_t i = 0; i + 1 < last.nodes.size(); i++) {
            const size_t spur = last.nodes[i];
            std::vector<bool> er(edges.size(), false), nr(n, false);
            // Remove the next edge of every accepted path sharing this root.
            for (const auto& p : A)
                if (p.nodes.size() > i &&
                    std::equal(p.edges.begin(), p.edges.begin() + i, last.edges.begin()))
                    er[p.edges[i]] = true;
            // The root's nodes (before the spur) may not be revisited: loopless.
            double rootLen = 0;
            for (size_t j = 0; j < i; j++) {
                nr[last.nodes[j]] = true;
                rootLen += edges[last.edges[j]].length;
            }
            TGraphPath sp = dijkstra(adj, edges, spur, target, er, nr, heuristic);
            if (sp.nodes.empty())
                continue;
            TGraphPath total;
            total.edges.assign(last.edges.begin(), last.edges.begin() + i);
            total.edges.insert(total.edges.end(), sp.edges.begin(), sp.edges.end());
            total.nodes.assign(last.nodes.begin(), last.nodes.begin() + i);
            total.nodes.insert(total.nodes.end(), sp.nodes.begin(), sp.nodes.end());
            total.length = rootLen + sp.length;
            B.insert(total);
        }
        // The best candidate not already accepted.
        while (!B.empty() && std::any_of(A.begin(), A.end(), [&](const TGraphPath& p) {
            return p.edges == B.begin()->edges;
        }))
            B.erase(B.begin());
        if (B.empty())
            break;
        A.push_back(*B.begin());
        B.erase(B.begin());
    }
    return A;
}

}  // namespace risknav::geometry
