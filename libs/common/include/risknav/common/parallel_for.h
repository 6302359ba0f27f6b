#pragma once
#include <cstddef>
#include <functional>

namespace risknav::common {
/** Runs body(0), ..., body(n - 1), in any order and possibly on several
 * threads, and returns when all have run (rethrowing the first exception
 * one ended with). An empty TParallelFor: parallelFor() below runs the bodies
 * in order on the calling thread. Each body must
 * write only its own outputs, so the result is the same on any thread. */
using TParallelFor =
    std::function<void(size_t n, const std::function<void(size_t)>& body)>;

/** body(0..n-1) in order on the calling thread; `parallel` when set. */
inline void parallelFor(const TParallelFor& parallel, size_t n,
                        const std::function<void(size_t)>& body) {
    if (parallel) {
        parallel(n, body);
        return;
    }
    for (size_t i = 0; i < n; i++)
        body(i);
}
}  // namespace risknav::common
