// libFuzzer target: the map loaders, risknav::common::loadOccupancyGrid().
// The first input byte selects the format, the rest is the file:
//   byte % 4 == 0: bitmap (.png; OpenCV also reads PGM/BMP content)
//   byte % 4 == 1: .gridmap     (MRPT serialized COccupancyGridMap2D, plain)
//   byte % 4 == 2: .gridmap.gz  (the same, gz-compressed)
//   byte % 4 == 3: ROS map_server .yaml; a small valid PNG is written beside
//                  it (as map.png) so that `image: map.png` resolves.
// Documented failures: CBadInputError. Anything else is a finding.
#include "fuzz_common.h"

#include <sys/stat.h>

#include <risknav/common/CBadInputError.h>
#include <risknav/common/grid_io.h>

#include <stdexcept>

using namespace risknav;

namespace {
// 8 x 8 8-bit grey PNG: a black border around white (a closed room).
const unsigned char kRoomPng[] = {
#include "room_png.inc"
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1)
        return 0;
    static const std::string base = fuzz::tempPath("map");
    static const std::string dir = [] {
        const std::string d = fuzz::tempPath("mapdir");
        ::mkdir(d.c_str(), 0755);
        fuzz::writeFile(d + "/map.png", kRoomPng, sizeof(kRoomPng));
        return d;
    }();
    static const char* const kExt[] = {".png", ".gridmap", ".gridmap.gz", ".yaml"};
    const int fmt = data[0] % 4;
    common::TMapSourceOptions src;
    src.map_file = fmt == 3 ? dir + "/map.yaml" : base + kExt[fmt];
    src.map_resolution = 0.05;
    fuzz::writeFile(src.map_file, data + 1, size - 1);
    try {
        const auto g = common::loadOccupancyGrid(src);
        (void)g.getSizeX();
    } catch (const common::CBadInputError&) {
    }
    return 0;
}
