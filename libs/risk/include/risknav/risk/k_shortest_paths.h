#pragma once
#include <cstddef>
#include <vector>

namespace risknav::risk {
/** An undirected multigraph edge (parallel edges allowed: two corridors
 * between the same junctions are different routes). */
struct TGraphEdge {
    size_t a = 0, b = 0;
    double length = 0;
};

/** A path as the list of edge ids from source to target, with its node sequence. */
struct TGraphPath {
    std::vector<size_t> edges, nodes;
    double length = 0;
};

/** Dijkstra on the undirected multigraph; edges/nodes flagged in the masks are
 * skipped. Returns an empty path (no nodes) when the target is unreachable. */
TGraphPath shortestPath(size_t nNodes, const std::vector<TGraphEdge>& edges,
                        size_t source, size_t target,
                        const std::vector<bool>& edgeRemoved,
                        const std::vector<bool>& nodeRemoved);

/** Yen's algorithm: the k shortest loopless paths from source to target, in
 * increasing length (ties in a deterministic order). Fewer if fewer exist.
 * (Yen 1971; the k-shortest-paths answer Yamashita et al. (M4) ask for, used
 * here for the GVG candidates of Irie et al. (M2).) */
std::vector<TGraphPath> kShortestPaths(size_t nNodes,
                                       const std::vector<TGraphEdge>& edges,
                                       size_t source, size_t target, size_t k);

}  // namespace risknav::risk
