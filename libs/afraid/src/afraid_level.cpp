#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/afraid/afraid_level.h>

#include <algorithm>
#include <cmath>

namespace risknav::afraid {
std::vector<TKrrSample> afraidSamples(const CAfraidGrid& g, double sampleBin) {
    // Pool passes and events in sampleBin x sampleBin squares first: the
    // robot's cells along a path are nearly one-dimensional and jitter
    // sideways with the localization; regressing on single cells would fit that
    // jitter. Each bin is a sample at its pass-weighted mean position with
    // target = events per pass through the bin. The events are those of the
    // unexpected obstacles, projected onto the robot's path (where the robot
    // meets them, whichever way it comes), and a pass through the bin enters
    // about `per` of its cells, so passes / per = passes through the bin.
    const int sx = g.sizeX(), sy = g.sizeY();
    const int per = std::max(1, int(std::lround(sampleBin / g.resolution())));
    const int bx = (sx + per - 1) / per, by = (sy + per - 1) / per;
    std::vector<double> ps(size_t(bx) * by, 0), ev(size_t(bx) * by, 0),
        mxs(size_t(bx) * by, 0), mys(size_t(bx) * by, 0);
    for (int cy = 0; cy < sy; cy++)
        for (int cx = 0; cx < sx; cx++) {
            const size_t k = size_t(cy) * sx + cx, b = size_t(cy / per) * bx + cx / per;
            const double p = g.passes()[k];
            ps[b] += p;
            ev[b] += g.obstacleEvents()[k];
            mxs[b] += p * g.colToX(cx);
            mys[b] += p * g.rowToY(cy);
        }
    // An event can fall one cell off the bins the robot's path runs through
    // (its projection onto the path vs the localized poses): a bin with
    // events and no passes gives them to its neighbour with the most passes.
    for (int y = 0; y < by; y++)
        for (int x = 0; x < bx; x++) {
            const size_t b = size_t(y) * bx + x;
            if (ev[b] == 0 || ps[b] > 0)
                continue;
            // The most passes; on a tie the nearest (side before corner).
            size_t best = b;
            int bestDist = 3;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= bx || ny >= by || (dx == 0 && dy == 0))
                        continue;
                    const size_t n = size_t(ny) * bx + nx;
                    const int dist = std::abs(dx) + std::abs(dy);
                    if (ps[n] > 0 && (best == b || ps[n] > ps[best] ||
                                      (ps[n] == ps[best] && dist < bestDist))) {
                        best = n;
                        bestDist = dist;
                    }
                }
            ev[best] += best != b ? ev[b] : 0.0;
        }
    std::vector<TKrrSample> samples;
    for (size_t b = 0; b < ps.size(); b++)
        if (ps[b] > 0)
            samples.push_back(
                {mxs[b] / ps[b], mys[b] / ps[b], std::min(1.0, ev[b] * per / ps[b])});
    return samples;
}

std::vector<float> afraidLevel(const CAfraidGrid& g, const TKrrOptions& krr,
                               double sampleBin) {
    const auto samples = afraidSamples(g, sampleBin);
    const auto alpha = krrFit(samples, krr);
    return krrPredictGrid(samples, alpha, krr, g.xMin(), g.yMin(), g.resolution(),
                          g.sizeX(), g.sizeY());
}

}  // namespace risknav::afraid
