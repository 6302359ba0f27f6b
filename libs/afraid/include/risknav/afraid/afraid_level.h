#pragma once
#include <risknav/afraid/kernel_regression.h>

#include <vector>

namespace risknav::afraid {
class CAfraidGrid;

/** The regression samples of an afraid grid: passes and obstacle events (the
 * unexpected obstacles projected onto the robot's path) pooled in square bins
 * of `sampleBin` metres (rounded to whole cells, at least one), one sample per
 * bin the robot passed through, at the bin's pass-weighted mean position, with
 * target = events per pass through the bin:
 *   target_b = min(1, (sum_b events) / ((sum_b passes) / per)),
 * per = the bin's side in cells (a pass enters about per cells of a bin). An
 * event in a bin without passes goes to its neighbour with the most passes.
 * The per-cell counts are eq. (12) of Choi, Chung, Song (002); pooling first
 * keeps the regression from fitting the sideways jitter of the localized path
 * (beyond the paper, whose robot keeps to a centre line). Samples are in bin
 * order (row-major). */
std::vector<TKrrSample> afraidSamples(const CAfraidGrid& g, double sampleBin);

/** The generalized afraid level per cell of `g` (row-major, g.sizeX() *
 * g.sizeY(), in events per pass): Gaussian-kernel ridge regression (Choi,
 * Chung, Song (002) section 2.5, Fig. 9; see kernel_regression.h) fitted on
 * afraidSamples(g, sampleBin) and evaluated at every cell centre. Pure: a
 * .afraid file gives its level map without MCL or rawlogs,
 *   afraidLevel(CAfraidGrid::load(path), krr, sampleBin),
 * equal to what the learner that wrote it computed with the same options. */
std::vector<float> afraidLevel(const CAfraidGrid& g, const TKrrOptions& krr,
                               double sampleBin);

}  // namespace risknav::afraid
