#pragma once
#include <cstdint>
#include <functional>
#include <optional>

namespace risknav::common {
/** Progress callback of a probe: "this many units are done". */
using TProbeProgress = std::function<void(std::uint64_t)>;

/** Runs `work` in a forked child process. Returns nullopt when the child
 *  finished (normally or by an exception), or, when it died (signal,
 *  sanitizer exit, abort), the last value it passed to its progress callback
 *  (0 if none): the first unit it could not finish.
 *
 *  Why: MRPT 2.5's deserializers dereference null pointers they read from a
 *  file (a rawlog's CActionCollection element or CActionRobotMovement2D pose
 *  PDF, a simplemap's keyframe pose, that is null or of another class), a
 *  signal no exception handler can catch. The readers read the file once in
 *  a child to learn whether, and where, that happens. The child writes
 *  nothing to stdout or stderr and leaves by _exit, so no destructor of the
 *  parent's objects (staged output folders, files) runs in it. */
std::optional<std::uint64_t> probeInChild(
    const std::function<void(const TProbeProgress&)>& work);
}  // namespace risknav::common
