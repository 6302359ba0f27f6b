// Seed maker for the fuzz corpora (scripts/fuzz.sh), not a fuzz target:
//   fuzz_make_seeds MAP_IMAGE OUT_DIR
// writes OUT_DIR/small-*.afraid (uncompressed .afraid content, what
// CAfraidGrid::decode() reads) on the map's geometry and a few cropped
// geometries, and OUT_DIR/small.gridmap.gz (the map as MRPT .gridmap.gz).
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/common/grid_io.h>

#include <cstdio>
#include <fstream>
#include <string>

using namespace risknav;

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s MAP_IMAGE OUT_DIR\n", argv[0]);
        return 2;
    }
    const std::string out = argv[2];
    try {
        common::TMapSourceOptions src;
        src.map_file = argv[1];
        src.map_resolution = 0.25;  // a coarse grid: small seeds
        const auto map = common::loadOccupancyGrid(src);
        common::saveGridmapGz(map, out + "/small.gridmap.gz");
        afraid::CAfraidGrid g(map);
        std::ofstream(out + "/small-empty.afraid", std::ios::binary) << g.encode();
        const double x0 = map.getXMin(), y0 = map.getYMin();
        const double x1 = map.getXMax(), y1 = map.getYMax();
        g.addPass(x0 + 0.3, y0 + 0.3);
        g.addTraversal(x0 + 0.3, y0 + 0.3, x1 - 0.3, y1 - 0.3);
        for (int i = 0; i < 5; ++i) {
            g.addExposure(x0 + 0.3 * (i + 1), y0 + 0.3);
            g.addRobotEvent(x0 + 0.3 * (i + 1), y0 + 0.3);
            g.addObstacleEvent(x0 + 0.3 * (i + 2), y0 + 0.6);
        }
        g.runs = 2;
        g.frames = 123;
        std::ofstream(out + "/small-events.afraid", std::ios::binary) << g.encode();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz_make_seeds: %s\n", e.what());
        return 1;
    }
    return 0;
}
