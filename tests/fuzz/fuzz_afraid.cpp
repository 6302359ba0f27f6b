// libFuzzer target: the .afraid loader, CAfraidGrid::decode() on the
// uncompressed file content (load() = gz inflate + decode()). Documented
// failure: CBadInputError. Anything else is a finding.
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/common/CBadInputError.h>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const auto g = risknav::afraid::CAfraidGrid::decode(bytes, "fuzz.afraid");
        (void)g.totalRobotEvents();
        (void)g.encode();
    } catch (const risknav::common::CBadInputError&) {
    }
    return 0;
}
