#pragma once
#include <cstddef>
#include <vector>

/** Weighted undirected graphs and their shortest paths: shared by the risk
 * evaluator (GVG candidate routes, M2) and the viewpoint planner (visibility
 * graph, M4), so it lives below both. */
namespace risknav::geometry {
/** A multigraph edge (parallel edges allowed: two corridors between the same
 * junctions are different routes), undirected unless `directed` (then only
 * a -> b: the viewpoint planner's tangent graph, where passing a corner
 * clockwise or counter-clockwise are different states). A graph is a node
 * count plus a list of these; an edge's id is its index in the list. */
struct TGraphEdge {
    size_t a = 0, b = 0;
    double length = 0;  ///< weight, >= 0
    bool directed = false;
};

/** A path as the list of edge ids from source to target, with its node sequence. */
struct TGraphPath {
    std::vector<size_t> edges, nodes;
    double length = 0;
};

/** Dijkstra on the undirected multigraph; edges/nodes flagged in the masks are
 * skipped (Yen's spur searches need that). Returns an empty path (no nodes)
 * when the target is unreachable. Preconditions (not checked, as in a hot
 * loop): every node id < nNodes, edgeRemoved.size() == edges.size(),
 * nodeRemoved.size() == nNodes. */
TGraphPath shortestPath(size_t nNodes, const std::vector<TGraphEdge>& edges,
                        size_t source, size_t target,
                        const std::vector<bool>& edgeRemoved,
                        const std::vector<bool>& nodeRemoved);

/** Dijkstra on the whole graph (nothing removed). */
TGraphPath shortestPath(size_t nNodes, const std::vector<TGraphEdge>& edges,
                        size_t source, size_t target);

/** Yen's algorithm: the k shortest loopless paths from source to target, in
 * increasing length (ties in a deterministic order). Fewer if fewer exist.
 * (Yen 1971; the k-shortest-paths answer Yamashita et al. (M4) ask for, also
 * used for the GVG candidates of Irie et al. (M2).) `heuristic`, when not
 * empty, holds per node a consistent lower bound of its distance to target
 * (h(u) <= length(u, v) + h(v), h(target) = 0; e.g. the straight-line
 * distance in a geometric graph): the spur searches are then A*, which finds
 * the same lengths and visits far fewer nodes (equal-length paths may come
 * in another order). */
std::vector<TGraphPath> kShortestPaths(size_t nNodes,
                                       const std::vector<TGraphEdge>& edges,
                                       size_t source, size_t target, size_t k,
                                       const std::vector<double>& heuristic = {});

}  // namespace risknav::geometry
