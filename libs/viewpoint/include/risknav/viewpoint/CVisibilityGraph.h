#pragma once
#include <risknav/geometry/CSegmentIndex.h>
#include <risknav/geometry/graph.h>
#include <risknav/viewpoint/TPolygonWorld.h>

#include <mrpt/math/TPoint2D.h>

#include <vector>

namespace risknav::viewpoint {
/** The visibility graph of the C-obstacles grown by a safety distance
 * D_s = R + S (Yamashita et al. 004 section IV-A, Fig. 7).
 *
 * C-obstacles: every obstacle (and the outer wall) grown by D_s, the rounded
 * corners approximated by polygons ("shapes of their vertices are
 * approximated with the polygons"). The corner polygon is circumscribed: its
 * edges are tangent to the true arc, so it contains the true grown obstacle
 * and every node lies at >= D_s from every obstacle. Only convex corners get
 * nodes (a shortest path never bends at a reflex corner); a node inside
 * another C-obstacle is dropped.
 *
 * Edges: beyond the paper, only bitangent ones (the segment is a supporting
 * line of the C-obstacle at both ends: the reduced visibility graph, which
 * holds every shortest and every taut path), and a segment is free when its
 * exact distance to every obstacle edge is >= D_s (the rounded C-obstacle,
 * not its polygon: safe, and a path may cut across the polygon's corner by
 * less than its circumscription). So every path point keeps >= D_s from
 * every obstacle, exactly.
 *
 * Also beyond the paper, the graph is the directed tangent graph: each corner
 * node is split into "passing it with the obstacle on the left" and "... on
 * the right", and an edge arrives in and leaves from the state its side
 * gives. A path then only bends around obstacles (taut); on the plain
 * visibility graph most of the k shortest simple paths are the shortest one
 * with a detour that turns back on itself. */
class CVisibilityGraph {
  public:
    struct TNode {
        mrpt::math::TPoint2D p;
        mrpt::math::TPoint2D tin, tout;  ///< boundary directions at a corner node
        mrpt::math::TPoint2D centre;     ///< the obstacle corner it goes round
        bool corner = true;              ///< false for start and goal
    };

    /** `edges`: the world's obstacle edges (TPolygonWorld::edges()) indexed;
     * clearance = D_s [m] > 0; segmentsPerCircle >= 4: corner polygon
     * resolution (a full turn in that many edges). */
    CVisibilityGraph(const TPolygonWorld& world, const geometry::CSegmentIndex& edges,
                     double clearance, int segmentsPerCircle,
                     const mrpt::math::TPoint2D& start, const mrpt::math::TPoint2D& goal);

    const std::vector<TNode>& nodes() const { return m_nodes; }
    /** The undirected visibility edges between nodes (for pictures). */
    const std::vector<geometry::TGraphEdge>& edges() const { return m_edges; }
    size_t startNode() const { return m_start; }
    size_t goalNode() const { return m_goal; }
    /** Is the point at >= D_s from every obstacle and not inside one? */
    bool pointFree(const mrpt::math::TPoint2D& p) const;
    bool startFree() const { return m_startFree; }
    bool goalFree() const { return m_goalFree; }

    /** Is the straight segment free (>= D_s from every obstacle edge)? */
    bool segmentFree(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b) const;
    /** Is the segment a supporting line of node i's C-obstacle there? */
    bool supports(size_t i, const mrpt::math::TPoint2D& dir) const;

    /** The k shortest simple paths start -> goal (Yen's algorithm, the shared
     * risknav::geometry code, on the directed tangent graph) as polylines;
     * a path that passes one corner node twice (once each way round), that
     * bends away from a corner it is tangent to, or that repeats an earlier
     * path's polyline (coincident nodes, straight-on vertices) is dropped (Yen is
     * asked for 2 k + 4 paths, then twice as many while that leaves fewer
     * than k, up to 16 (k + 4)); its spur searches are A* with the
     * straight-line distance to the goal. Empty when start or goal is not free
     * or the goal cannot be reached. */
    std::vector<std::vector<mrpt::math::TPoint2D>> kShortestPaths(size_t k) const;

  private:
    /** The polyline of a node path without repeated points and straight-on
     * vertices (so that one route has one polyline). */
    std::vector<mrpt::math::TPoint2D> canonicalPolyline(
        const std::vector<size_t>& nodes) const;
    /** Does the path (split nodes) bend toward the obstacle at every corner? */
    bool taut(const std::vector<size_t>& splitNodes) const;

    const TPolygonWorld& m_world;
    const geometry::CSegmentIndex& m_index;
    double m_d;
    std::vector<TNode> m_nodes;
    std::vector<geometry::TGraphEdge> m_edges;
    std::vector<geometry::TGraphEdge> m_directed;  // split nodes: 2i (left), 2i+1 (right)
    size_t m_start = 0, m_goal = 0;
    bool m_startFree = false, m_goalFree = false;
};

}  // namespace risknav::viewpoint
