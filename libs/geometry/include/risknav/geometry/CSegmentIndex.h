#pragma once
#include <risknav/geometry/segments.h>

#include <cstdint>
#include <vector>

namespace risknav::geometry {
/** A uniform bucket grid over a fixed set of segments (obstacle edges), for
 * the two queries a polygon planner asks millions of times: how far is this
 * point from the nearest segment, and does this segment come closer than d to
 * any of them. Exact answers (the grid only decides which segments to test).
 * Queries are const and thread-safe. */
class CSegmentIndex {
  public:
    CSegmentIndex() = default;
    /** cellSize [m] > 0: about the typical query distance works well. */
    CSegmentIndex(std::vector<TSegment> segments, double cellSize);

    const std::vector<TSegment>& segments() const { return m_segs; }
    bool empty() const { return m_segs.empty(); }

    /** Distance from p to the nearest segment, searched out to `cap` [m]:
     * returns min(true distance, cap); +inf cap searches everything. */
    double distance(const mrpt::math::TPoint2D& p, double cap) const;

    /** Is some segment at distance < d from the segment [a, b]? (d = 0: does
     * some segment touch it.) */
    bool anyWithin(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
                   double d) const;

  private:
    std::vector<TSegment> m_segs;
    double m_cell = 1, m_x0 = 0, m_y0 = 0;
    int m_nx = 0, m_ny = 0;
    std::vector<uint32_t> m_start;  // CSR: cell -> [m_start[c], m_start[c+1]) in m_items
    std::vector<uint32_t> m_items;  // segment ids

    int col(double x) const;
    int row(double y) const;
};

}  // namespace risknav::geometry
