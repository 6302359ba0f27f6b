#pragma once
#include <risknav/common/probe_in_child.h>

#include <cstdint>
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

/** The probe's progress callback (risknav/common/probe_in_child.h). */
using TProbeProgress = common::TProbeProgress;
}  // namespace risknav::localization
