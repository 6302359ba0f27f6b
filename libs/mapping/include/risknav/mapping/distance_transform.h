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
}  // namespace risknav::mapping
