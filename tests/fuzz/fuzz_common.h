// Shared helpers of the libFuzzer harnesses (tests/fuzz, built only with
// -DRISKNAV_BUILD_FUZZERS=ON, see scripts/fuzz.sh).
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

namespace risknav::fuzz {
/** /tmp/risknav-fuzz-<PID>-<name>: one file per fuzzer process and name. */
inline std::string tempPath(const std::string& name) {
    return "/tmp/risknav-fuzz-" + std::to_string(::getpid()) + "-" + name;
}

/** Writes the bytes to path (truncating); returns path. */
inline std::string writeFile(const std::string& path, const uint8_t* data, size_t size) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path;
}
inline std::string writeFile(const std::string& path, const std::string& text) {
    return writeFile(path, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}
}  // namespace risknav::fuzz
