#include <risknav/geometry/CSegmentIndex.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

using mrpt::math::TPoint2D;

namespace risknav::geometry {
namespace {
// Cells per side are capped so that a huge map with a tiny cell cannot ask
// for an unbounded grid; the cell grows instead.
constexpr long kMaxCells = 1L << 22;
}  // namespace

CSegmentIndex::CSegmentIndex(std::vector<TSegment> segs, double cellSize)
    : m_segs(std::move(segs)) {
    if (!(cellSize > 0) || !std::isfinite(cellSize))
        throw std::invalid_argument("CSegmentIndex: cellSize must be > 0");
    if (m_segs.empty())
        return;
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const auto& s : m_segs) {
        x0 = std::min({x0, s.a.x, s.b.x});
        x1 = std::max({x1, s.a.x, s.b.x});
        y0 = std::min({y0, s.a.y, s.b.y});
        y1 = std::max({y1, s.a.y, s.b.y});
    }
    m_cell = cellSize;
    while ((long(std::floor((x1 - x0) / m_cell)) + 1) *
               (long(std::floor((y1 - y0) / m_cell)) + 1) >
           kMaxCells)
        m_cell *= 2;
    m_x0 = x0;
    m_y0 = y0;
    m_nx = int(std::floor((x1 - x0) / m_cell)) + 1;
    m_ny = int(std::floor((y1 - y0) / m_cell)) + 1;
    // Each segment goes into every cell its bounding box covers, row by row
    // only over the columns the segment itself crosses in that row.
    std::vector<std::vector<uint32_t>> cells(size_t(m_nx) * size_t(m_ny));
    for (uint32_t i = 0; i < m_segs.size(); i++) {
        const auto& s = m_segs[i];
        const int r0 = row(std::min(s.a.y, s.b.y)), r1 = row(std::max(s.a.y, s.b.y));
        for (int r = r0; r <= r1; r++) {
            // x-range of the segment inside the row band [ya, yb].
            const double ya = m_y0 + r * m_cell, yb = ya + m_cell;
            double xa = std::min(s.a.x, s.b.x), xb = std::max(s.a.x, s.b.x);
            if (s.a.y != s.b.y) {
                const double ta = (ya - s.a.y) / (s.b.y - s.a.y);
                const double tb = (yb - s.a.y) / (s.b.y - s.a.y);
                const double t0 = std::clamp(std::min(ta, tb), 0.0, 1.0);
                const double t1 = std::clamp(std::max(ta, tb), 0.0, 1.0);
                const double u0 = s.a.x + t0 * (s.b.x - s.a.x);
                const double u1 = s.a.x + t1 * (s.b.x - s.a.x);
                xa = std::min(u0, u1);
                xb = std::max(u0, u1);
            }
            for (int c = col(xa); c <= col(xb); c++)
                cells[size_t(r) * size_t(m_nx) + size_t(c)].push_back(i);
        }
    }
    m_start.assign(cells.size() + 1, 0);
    for (size_t c = 0; c < cells.size(); c++)
        m_start[c + 1] = m_start[c] + uint32_t(cells[c].size());
    m_items.reserve(m_start.back());
    for (const auto& c : cells)
        m_items.insert(m_items.end(), c.begin(), c.end());
}

int CSegmentIndex::col(double x) const {
    return std::clamp(int(std::floor((x - m_x0) / m_cell)), 0, m_nx - 1);
}
int CSegmentIndex::row(double y) const {
    return std::clamp(int(std::floor((y - m_y0) / m_cell)), 0, m_ny - 1);
}

double CSegmentIndex::distance(const TPoint2D& p, double cap) const {
    if (m_segs.empty())
        return cap;
    double best = cap;
    // Distance from p to the grid's box: rings of cells start there.
    const double gx = std::max({m_x0 - p.x, 0.0, p.x - (m_x0 + m_nx * m_cell)});
    const double gy = std::max({m_y0 - p.y, 0.0, p.y - (m_y0 + m_ny * m_cell)});
    if (std::hypot(gx, gy) >= best)
        return best;
    const int cx = col(p.x), cy = row(p.y);
    const int maxRing = std::max(m_nx, m_ny);
    auto scan = [&](int r, int c) {
        if (r < 0 || r >= m_ny || c < 0 || c >= m_nx)
            return;
        const size_t cell = size_t(r) * size_t(m_nx) + size_t(c);
        for (uint32_t k = m_start[cell]; k < m_start[cell + 1]; k++) {
            const auto& s = m_segs[m_items[k]];
            best = std::min(best, pointSegmentDistance(p, s.a, s.b));
        }
    };
    for (int ring = 0; ring <= maxRing; ring++) {
        // Cells of Chebyshev ring k around p's (clamped) cell are at least
        // (k - 1) cells away from p.
        if (ring >= 1 && (ring - 1) * m_cell >= best)
            break;
        if (ring == 0) {
            scan(cy, cx);
            continue;
        }
        for (int c = cx - ring; c <= cx + ring; c++) {
            scan(cy - ring, c);
            scan(cy + ring, c);
        }
        for (int r = cy - ring + 1; r <= cy + ring - 1; r++) {
            scan(r, cx - ring);
            scan(r, cx + ring);
        }
    }
    return best;
}

bool CSegmentIndex::anyWithin(const TPoint2D& a, const TPoint2D& b, double d) const {
    if (m_segs.empty())
        return false;
    const double ylo = std::min(a.y, b.y) - d, yhi = std::max(a.y, b.y) + d;
    if (yhi < m_y0 || ylo > m_y0 + m_ny * m_cell)
        return false;
    const int r0 = row(ylo), r1 = row(yhi);
    for (int r = r0; r <= r1; r++) {
        // x-range of the segment thickened by d inside this row band.
        const double ya = m_y0 + r * m_cell - d, yb = m_y0 + (r + 1) * m_cell + d;
        double t0 = 0, t1 = 1;
        if (a.y != b.y) {
            const double ta = (ya - a.y) / (b.y - a.y), tb = (yb - a.y) / (b.y - a.y);
            t0 = std::max(0.0, std::min(ta, tb));
            t1 = std::min(1.0, std::max(ta, tb));
            if (t0 > t1)
                continue;
        } else if (a.y < ya || a.y > yb)
            continue;
        const double u0 = a.x + t0 * (b.x - a.x), u1 = a.x + t1 * (b.x - a.x);
        const double xlo = std::min(u0, u1) - d, xhi = std::max(u0, u1) + d;
        if (xhi < m_x0 || xlo > m_x0 + m_nx * m_cell)
            continue;
        const int c1 = col(xhi);
        for (int c = col(xlo); c <= c1; c++) {
            const size_t cell = size_t(r) * size_t(m_nx) + size_t(c);
            for (uint32_t k = m_start[cell]; k < m_start[cell + 1]; k++) {
                const auto& s = m_segs[m_items[k]];
                if (segmentSegmentDistance(a, b, s.a, s.b) < d ||
                    (d <= 0 && segmentsIntersect(a, b, s.a, s.b)))
                    return true;
            }
        }
    }
    return false;
}

}  // namespace risknav::geometry
