#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace risknav::localization {
/** What one pass over a rawlog's bytes tells before MRPT reads it. */
struct TRawlogSize {
    /** Decompressed bytes that decode: bounds what any entry can justify
     *  allocating. */
    std::uint64_t bytes = 0;
    /** The gzip stream breaks after `bytes` (MRPT reads such a file to that
     *  point and then reports a clean end of file). */
    bool broken = false;
};

/** One pass over a rawlog (plain or gzip). Throws std::runtime_error naming
 *  the file if it cannot be opened. */
TRawlogSize rawlogBytes(const std::string& path);

/** Progress callback of a probe: "this many units are done". */
using TProbeProgress = std::function<void(std::uint64_t)>;

/** Runs `work` in a forked child process. Returns nullopt when the child
 *  finished (normally or by an exception), or, when it died (signal,
 *  sanitizer exit, abort), the last value it passed to its progress callback
 *  (0 if none): the first unit it could not finish.
 *
 *  Why: MRPT 2.5's deserializers dereference null pointers they read from a
 *  file (a CActionCollection element, or a CActionRobotMovement2D pose PDF,
 *  that is null or of another class: its `deepcopy_poly_ptr` clones it), a
 *  signal no exception handler can catch. The rawlog reader reads the file
 *  once in a child to learn which entry, if any, does that. The child writes
 *  nothing to stdout or stderr and leaves by _exit, so no destructor of the
 *  parent's objects (staged output folders, files) runs in it. */
std::optional<std::uint64_t> probeInChild(
    const std::function<void(const TProbeProgress&)>& work);
}  // namespace risknav::localization
