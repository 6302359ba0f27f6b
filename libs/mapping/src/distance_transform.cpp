#include <risknav/mapping/distance_transform.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace risknav::mapping {
namespace {
/** Both transforms' first pass, along the columns, all columns at once row
 * by row (contiguous, branch-free): per cell the distance in cells to the
 * nearest source in its column (the ring outside the grid one cell beyond
 * the first and last rows when `borderIsSource`), capped at `cap` >= 1. */
void columnDistances(const std::vector<uint8_t>& source, int w, int h,
                     bool borderIsSource, int32_t cap, std::vector<int32_t>& col) {
    col.resize(source.size());
    const int32_t edge = borderIsSource ? 1 : cap;
    for (int i = 0; i < w; i++)
        col[size_t(i)] = source[size_t(i)] ? 0 : edge;
    for (int j = 1; j < h; j++) {
        const uint8_t* s = &source[size_t(j) * w];
        const int32_t* up = &col[size_t(j - 1) * w];
        int32_t* c = &col[size_t(j) * w];
        for (int i = 0; i < w; i++)
            c[i] = s[i] ? 0 : std::min(up[i] + 1, cap);
    }
    {
        int32_t* c = &col[size_t(h - 1) * w];
        for (int i = 0; i < w; i++)
            c[i] = std::min(c[i], edge);
    }
    for (int j = h - 2; j >= 0; j--) {
        const int32_t* down = &col[size_t(j + 1) * w];
        int32_t* c = &col[size_t(j) * w];
        for (int i = 0; i < w; i++)
            c[i] = std::min(c[i], down[i] + 1);
    }
}
}  // namespace

void squaredDistanceTransform(const std::vector<uint8_t>& source, int w, int h,
                              bool borderIsSource, std::vector<int32_t>& out) {
    if (w < 0 || h < 0 || source.size() != size_t(w) * size_t(h))
        throw std::invalid_argument("distance transform: source is not w x h");
    out.assign(source.size(), kNoSource);
    if (source.empty())
        return;
    // Pass 1: the column distances; kFar (> any real one, and kFar + 1 does
    // not overflow) for none.
    const int32_t kFar = 1 << 24;
    std::vector<int32_t> col;
    columnDistances(source, w, h, borderIsSource, kFar, col);
    // Pass 2, along each row: the lower envelope of the parabolas
    // (x - q)^2 + f(q), f(q) = col(q)^2, over the cells q that have one
    // (and the border cells q = -1 and q = w with f = 0 when the border is a
    // source). Exact integers: a breakpoint is kept as a fraction
    // num / den (den > 0) and compared by cross-multiplication.
    const size_t cap = size_t(w) + 2;
    std::vector<int64_t> vq(cap), vh(cap), zn(cap), zd(cap);  // vh = f(q) + q^2
    for (int j = 0; j < h; j++) {
        const int32_t* c = &col[size_t(j) * w];
        int32_t* o = &out[size_t(j) * w];
        int k = -1;  // the last parabola of the envelope; z[0] = -inf
        auto push = [&](int64_t q, int64_t f) {
            const int64_t hq = f + q * q;
            int64_t num = 0, den = 1;
            while (k >= 0) {
                num = hq - vh[size_t(k)];
                den = 2 * (q - vq[size_t(k)]);
                // parabola k is nowhere the lowest: it meets the new one at
                // or before where it meets parabola k - 1
                if (k > 0 && num * zd[size_t(k)] <= zn[size_t(k)] * den)
                    k--;
                else
                    break;
            }
            k++;
            vq[size_t(k)] = q;
            vh[size_t(k)] = hq;
            zn[size_t(k)] = num;
            zd[size_t(k)] = den;
        };
        if (borderIsSource)
            push(-1, 0);
        // A source inside a run of sources (its row neighbours sources too)
        // is lowest only at its own cell, which is 0 anyway: not pushed
        // (most of a map that is still unknown is such runs).
        for (int i = 0; i < w; i++)
            if (c[i] < kFar &&
                !(c[i] == 0 && i > 0 && i + 1 < w && c[i - 1] == 0 && c[i + 1] == 0))
                push(i, int64_t(c[i]) * c[i]);
        if (borderIsSource)
            push(w, 0);
        if (k < 0)
            continue;  // no source in this row's reach
        // each cell takes the envelope's parabola over it: the next one
        // starts where x > its breakpoint, i.e. x * den > num
        int e = 0;
        for (int64_t x = 0; x < w; x++) {
            while (e < k && x * zd[size_t(e) + 1] > zn[size_t(e) + 1])
                e++;
            if (c[x] == 0) {
                o[x] = 0;
                continue;
            }
            const int64_t d = x - vq[size_t(e)];
            const int64_t v = d * d + vh[size_t(e)] - vq[size_t(e)] * vq[size_t(e)];
            o[x] = v >= int64_t(kNoSource) ? kNoSource : int32_t(v);
        }
    }
}

namespace {
/** boundedSquaredDistanceTransform()'s row pass: per row, best(i) = min over
 * |d| <= reach of d^2 + col(i + d)^2, with the squares padded by `reach`
 * cells each side: the ring (0, a source one column out; farther pad cells
 * are never nearer than it) or none (kFar). T = int16_t for reach <= 127
 * (kFar + reach^2 < 2^15: eight lanes a vector, and SSE2 has their min),
 * else int32_t. */
template <typename T, typename TOut, typename TEmit>
void boundedRows(const std::vector<int32_t>& col, int w, int h, bool borderIsSource,
                 int reach, std::vector<TOut>& out, TEmit emit) {
    const T kFar = T(sizeof(T) == 2 ? 1 << 14 : 1 << 28);
    const int32_t reach2 = reach * reach;
    std::vector<T> sq(size_t(w) + 2 * size_t(reach)), best(static_cast<size_t>(w));
    const T pad = borderIsSource ? T(0) : kFar;
    std::fill(sq.begin(), sq.begin() + reach, pad);
    std::fill(sq.end() - reach, sq.end(), pad);
    for (int j = 0; j < h; j++) {
        const int32_t* c = &col[size_t(j) * w];
        T* q = sq.data() + reach;
        for (int i = 0; i < w; i++)
            q[i] = c[i] <= reach ? T(c[i] * c[i]) : kFar;
        // only the cells between the row's first and last non-source cells
        // need the minimum (a source cell is 0 whatever its neighbours: a
        // speed-up, the same values; most of a clearance row is non-free)
        int lo = 0, hi = w - 1;
        while (lo <= hi && c[lo] == 0)
            lo++;
        while (hi >= lo && c[hi] == 0)
            hi--;
        TOut* o = &out[size_t(j) * w];
        const TOut atSource = emit(0);
        std::fill(o, o + lo, atSource);
        std::fill(o + hi + 1, o + w, atSource);
        if (lo > hi)
            continue;
        T* b = best.data();
        std::copy(q + lo, q + hi + 1, b + lo);
        for (int d = 1; d <= reach; d++) {
            const T d2 = T(d * d);
            const T* left = q - d;
            const T* right = q + d;
            for (int i = lo; i <= hi; i++)
                b[i] = std::min(b[i], T(std::min(left[i], right[i]) + d2));
        }
        for (int i = lo; i <= hi; i++)
            o[i] = emit(int32_t(b[i]) <= reach2 ? int32_t(b[i]) : kNoSource);
    }
}

/** The checks and the column pass both bounded transforms share; then the
 * rows' pass, each cell's squared distance (or kNoSource) through `emit`. */
template <typename TOut, typename TEmit>
void boundedTransform(const std::vector<uint8_t>& source, int w, int h,
                      bool borderIsSource, int reach, std::vector<TOut>& out, TOut none,
                      TEmit emit) {
    if (w < 0 || h < 0 || source.size() != size_t(w) * size_t(h))
        throw std::invalid_argument("distance transform: source is not w x h");
    if (reach < 0 || reach > 4096)
        throw std::invalid_argument("bounded distance transform: reach must be 0..4096");
    out.assign(source.size(), none);
    if (source.empty())
        return;
    // Column distances as in squaredDistanceTransform(), capped at reach + 1
    // ("none within reach"); the rows' pass then takes their squares.
    std::vector<int32_t> col;
    columnDistances(source, w, h, borderIsSource, reach + 1, col);
    if (reach <= 127)
        boundedRows<int16_t>(col, w, h, borderIsSource, reach, out, emit);
    else
        boundedRows<int32_t>(col, w, h, borderIsSource, reach, out, emit);
}
}  // namespace

void boundedSquaredDistanceTransform(const std::vector<uint8_t>& source, int w, int h,
                                     bool borderIsSource, int reach,
                                     std::vector<int32_t>& out) {
    boundedTransform(source, w, h, borderIsSource, reach, out, kNoSource,
                     [](int32_t d2) { return d2; });
}

void boundedDistanceTransform(const std::vector<uint8_t>& source, int w, int h,
                              bool borderIsSource, int reach,
                              const std::vector<float>& valueOf, float none,
                              std::vector<float>& out) {
    if (reach >= 0 && reach <= 4096 && valueOf.size() != size_t(reach) * reach + 1)
        throw std::invalid_argument(
            "bounded distance transform: the value table needs reach^2 + 1 entries");
    boundedTransform(source, w, h, borderIsSource, reach, out, none,
                     [&valueOf, none](int32_t d2) {
                         return d2 == kNoSource ? none : valueOf[size_t(d2)];
                     });
}
}  // namespace risknav::mapping
