#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/afraid/afraid_level.h>

#include <algorithm>
#include <cmath>

namespace risknav::afraid {
std::vector<TKrrSample> afraidSamples(const CAfraidGrid& g, double sampleBin) {
    // Pool exposure and events in sampleBin x sampleBin squares first: the
    // robot's cells along a path are nearly one-dimensional and jitter
    // sideways with the localization; regressing on single cells would fit that
    // jitter. Each bin is a sample at its exposure-weighted mean position with
    // target events / exposure = events per pass through the bin.
    const int sx = g.sizeX(), sy = g.sizeY();
    const int per = std::max(1, int(std::lround(sampleBin / g.resolution())));
    const int bx = (sx + per - 1) / per, by = (sy + per - 1) / per;
    std::vector<double> ex(size_t(bx) * by, 0), ev(size_t(bx) * by, 0),
        mxs(size_t(bx) * by, 0), mys(size_t(bx) * by, 0);
    for (int cy = 0; cy < sy; cy++)
        for (int cx = 0; cx < sx; cx++) {
            const size_t k = size_t(cy) * sx + cx, b = size_t(cy / per) * bx + cx / per;
            const double e = g.exposure()[k];
            ex[b] += e;
            ev[b] += g.robotEvents()[k];
            mxs[b] += e * g.colToX(cx);
            mys[b] += e * g.rowToY(cy);
        }
    // A bin's exposure counts frames; a pass spends about per cells' worth of
    // frames in it, so events / (exposure / cells crossed) = events per pass.
    std::vector<TKrrSample> samples;
    for (size_t b = 0; b < ex.size(); b++)
        if (ex[b] > 0)
            samples.push_back({mxs[b] / ex[b], mys[b] / ex[b], ev[b] * per / ex[b]});
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
