// libFuzzer target: the map image reader (header size check of PNG, BMP,
// PGM/PPM/PBM, JPEG and TIFF before OpenCV decodes), through
// risknav::common::loadOccupancyGrid(). The input is the image file; OpenCV
// picks the decoder from its content, not its name.
// Documented failures: CBadInputError. Anything else is a finding.
#include "fuzz_common.h"

#include <risknav/common/CBadInputError.h>
#include <risknav/common/grid_io.h>

using namespace risknav;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string file = fuzz::tempPath("map.img");
    fuzz::writeFile(file, data, size);
    common::TMapSourceOptions src;
    src.map_file = file;
    src.map_resolution = 0.05;
    try {
        const auto g = common::loadOccupancyGrid(src);
        (void)g.getSizeX();
    } catch (const common::CBadInputError&) {
    }
    return 0;
}
