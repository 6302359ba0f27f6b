#pragma once
#include <cstdint>
#include <limits>
#include <vector>

namespace risknav::mapping {
/** squaredDistanceTransform()'s value for a cell with no source to measure to. */
constexpr int32_t kNoSource = std::numeric_limits<int32_t>::max();

/** The exact squared Euclidean distance transform of Felzenszwalb &
 * Huttenlocher ("Distance transforms of sampled functions", Theory of
 * Computing 8, 2012): for each cell of a w x h row-major grid, the squared
 * distance, in cells, from its centre to the nearest centre of a cell where
 * `source` is nonzero (0 on a source). `borderIsSource`: the ring of cells
 * just outside the grid counts as sources. No source at all: every cell
 * kNoSource (one source anywhere gives every cell a finite value).
 * Integer arithmetic throughout, so the result is exact; single-threaded
 * (OpenCV's parallel transform, which this replaces on the per-cycle path,
 * spent more on waking its worker threads than it saved on a 200 x 200
 * grid on 2 cores). `out` is resized to w * h. */
void squaredDistanceTransform(const std::vector<uint8_t>& source, int w, int h,
                              bool borderIsSource, std::vector<int32_t>& out);

/** squaredDistanceTransform() where only the near sources matter: the same
 * exact value for every cell whose nearest source is at most `reach` cells
 * away (squared distance <= reach^2), kNoSource for every other cell. For a
 * consumer that only compares the distance with a bound (which the full
 * transform's lower envelope cannot exploit): per row, the minimum over the
 * 2 reach + 1 column distances around each cell, contiguous loops the
 * compiler vectorizes; for a reach of ~10 cells a fraction of the full
 * transform's time on a 200 x 200 grid (tests/benchmarks/bench_speed.cpp).
 * Exact because a source within `reach` lies within `reach` columns and
 * rows. Throws std::invalid_argument for reach < 0 or > 4096, or a source
 * that is not w x h. */
void boundedSquaredDistanceTransform(const std::vector<uint8_t>& source, int w, int h,
                                     bool borderIsSource, int reach,
                                     std::vector<int32_t>& out);

/** boundedSquaredDistanceTransform() read through a table: each cell's
 * `valueOf[d2]` for its squared distance d2 <= reach^2, `none` beyond (e.g.
 * a distance in metres, one look-up instead of a pass over the squared
 * distances). `valueOf` must hold reach^2 + 1 entries (else, and as
 * boundedSquaredDistanceTransform(), std::invalid_argument). */
void boundedDistanceTransform(const std::vector<uint8_t>& source, int w, int h,
                              bool borderIsSource, int reach,
                              const std::vector<float>& valueOf, float none,
                              std::vector<float>& out);
}  // namespace risknav::mapping
