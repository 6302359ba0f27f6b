#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/risk/CObstacleField.h>

#include <mrpt/math/TPoint2D.h>

#include <cstdint>
#include <string>
#include <vector>

namespace risknav::risk {
/** Candidate routes along the Generalized Voronoi Graph of the free space
 * (Irie et al. (001) section 6.1, eq. 31: points equidistant from their two
 * closest obstacles), own implementation: MRPT 2.5.8's buildVoronoiDiagram
 * fails on non-square grids and at borders (MRPT_NOTES section 3).
 *
 * 1. The nearest obstacle cell of every free cell
 *    (mapping::CDistanceField::nearestObstacles(): the raw obstacles under the
 *    shared obstacle rule, the ring outside the map included by default, so
 *    that a map without a border wall has a GVG along its edges too).
 * 2. A free pixel is on the GVG when a 4-neighbour's nearest obstacle point
 *    lies far from its own: |N(p) - N(q)| >= max(2 cells, separation_ratio d(p))
 *    (the two sides of a corridor; the ratio prunes the spurs a medial axis
 *    grows towards corners), and the robot fits there (d(p) >= the field's
 *    robot radius).
 * 3. Zhang-Suen thinning to a one-pixel skeleton; each skeleton end is joined
 *    to the nearest pixel of another skeleton component within 2.5 x its
 *    clearance (where a corridor opens into a room the medial lines stop
 *    short of each other).
 * 4. Per query: start and goal join the nearest skeleton pixel they see in a
 *    straight, obstacle-free line; junctions become nodes, the branches
 *    between them edges; Yen's algorithm gives the shortest loopless routes,
 *    and the first k that go a different way around the obstacles than every
 *    shorter one (not homotopic: the loop they form encloses an obstacle) are
 *    kept, simplified (Douglas-Peucker, never across an obstacle). A branch
 *    inside one room makes a variant, not a distinct route. */
class CGvgRoutes {
  public:
    /** Keys gvg_separation_ratio and gvg_simplify_tolerance of the host
     * section ([RiskEval]), declared once in declare(). */
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "RiskEval"; }  // the host section

        double separation_ratio = 1.0;    ///< of the clearance, step 2 above
        double simplify_tolerance = 0.1;  ///< [m] Douglas-Peucker, step 4

      protected:
        void declare(Visitor& v) override;
    };

    /** Throws common::CConfigKeyError when the options are out of range. */
    CGvgRoutes(const CObstacleField& field, const TOptions& o);

    /** Up to k distinct routes start -> goal, shortest first (each starts at
     * start and ends at goal). Empty: no route (start or goal cannot reach the
     * GVG, or the GVG does not connect them). */
    std::vector<std::vector<mrpt::math::TPoint2D>> routes(
        const mrpt::math::TPoint2D& start, const mrpt::math::TPoint2D& goal,
        size_t k) const;

    /** The skeleton as a row-major mask (field geometry), for pictures. */
    const std::vector<uint8_t>& skeleton() const { return m_skel; }
    size_t skeletonCells() const { return m_pixels.size(); }

    /** Are two routes with the same ends the same way around the obstacles
     * (homotopic)? True when the closed loop a + reverse(b) encloses no raw
     * obstacle cell (geometry::sameHomotopy on this field). */
    bool sameWay(const std::vector<mrpt::math::TPoint2D>& a,
                 const std::vector<mrpt::math::TPoint2D>& b) const;

  private:
    void bridgeGaps(const mapping::TNearestObstacles& near);
    long attach(const mrpt::math::TPoint2D& p) const;  // skeleton pixel index or -1
    // Douglas-Peucker at simplify_tolerance, never across a grown obstacle.
    std::vector<mrpt::math::TPoint2D> simplify(
        const std::vector<mrpt::math::TPoint2D>& pts) const;
    const CObstacleField& m_field;
    TOptions m_opts;
    std::vector<uint8_t> m_skel;
    std::vector<uint32_t> m_pixels;  // indices of skeleton pixels
};

}  // namespace risknav::risk
