// libFuzzer target: the .simplemap reader (MRPT CSimpleMap, read in a forked
// probe and under an allocation budget, then turned into a grid), through
// risknav::common::loadOccupancyGrid(). The input is the (uncompressed) file.
// Documented failures: CBadInputError. Anything else is a finding.
#include "fuzz_common.h"

#include <risknav/common/CBadInputError.h>
#include <risknav/common/grid_io.h>

using namespace risknav;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string file = fuzz::tempPath("map.simplemap");
    fuzz::writeFile(file, data, size);
    common::TMapSourceOptions src;
    src.map_file = file;
    src.simplemap_resolution = 0.1;
    try {
        const auto g = common::loadOccupancyGrid(src);
        (void)g.getSizeX();
    } catch (const common::CBadInputError&) {
    }
    return 0;
}
