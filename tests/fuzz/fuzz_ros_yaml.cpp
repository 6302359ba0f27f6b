// libFuzzer target: the ROS map_server YAML reader (libyaml, each value
// checked), through risknav::common::loadOccupancyGrid(). The input is the
// .yaml file; a small valid PNG is written beside it (as map.png) so that
// `image: map.png` resolves.
// Documented failures: CBadInputError. Anything else is a finding.
#include "fuzz_common.h"

#include <sys/stat.h>

#include <risknav/common/CBadInputError.h>
#include <risknav/common/grid_io.h>

using namespace risknav;

namespace {
// 8 x 8 8-bit grey PNG: a black border around white (a closed room).
const unsigned char kRoomPng[] = {
#include "room_png.inc"
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string dir = [] {
        const std::string d = fuzz::tempPath("yamldir");
        ::mkdir(d.c_str(), 0755);
        fuzz::writeFile(d + "/map.png", kRoomPng, sizeof(kRoomPng));
        return d;
    }();
    common::TMapSourceOptions src;
    src.map_file = fuzz::writeFile(dir + "/map.yaml", data, size);
    try {
        const auto g = common::loadOccupancyGrid(src);
        (void)g.getSizeX();
    } catch (const common::CBadInputError&) {
    }
    return 0;
}
