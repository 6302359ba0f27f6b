#include <risknav/common/CAllocationBudget.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/config_read.h>
#include <risknav/common/grid_io.h>
#include <risknav/common/probe_in_child.h>

#include "grid_readers.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/serialization/CArchive.h>

#include <yaml.h>
#include <opencv2/imgcodecs.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using mrpt::maps::COccupancyGridMap2D;

namespace risknav::common {
void TMapSourceOptions::declare(Visitor& v) {
    v.path(map_file, "map_file", true,
           "the static map: .png/.pgm/.bmp, .gridmap(.gz), ROS .yaml or .simplemap(.gz)");
    v.number(map_resolution, "map_resolution", TRange::closed(0.001, 10, "m"),
             "a bitmap's pixel side");
    // Beyond a million metres MRPT's grid index arithmetic loses its cells.
    v.number(map_origin_x, "map_origin_x", TRange::closed(-1e6, 1e6, "m"),
             "world x of a bitmap's lower-left corner");
    v.number(map_origin_y, "map_origin_y", TRange::closed(-1e6, 1e6, "m"),
             "world y of a bitmap's lower-left corner");
    v.number(simplemap_resolution, "simplemap_resolution", TRange::closed(0.001, 10, "m"),
             "cell of a grid built from a .simplemap");
}

void TMapSourceOptions::validateRules() const {
    checkRule(!map_file.empty(), section, "map_file", map_file, "required");
}

namespace grid_readers {
std::string cellsText(uint64_t n) {
    return std::to_string(n / 1000000) + " M cells";
}

// (grid_readers.h)
std::pair<uint64_t, uint64_t> setSizeCells(float x0, float x1, float y0, float y1,
                                           float res) {
    if (!(res > 0 && x1 > x0 && y1 > y0) || !std::isfinite(x0) || !std::isfinite(x1) ||
        !std::isfinite(y0) || !std::isfinite(y1))
        return {0, 0};
    x0 = res * std::round(x0 / res);
    y0 = res * std::round(y0 / res);
    x1 = res * std::round(x1 / res);
    y1 = res * std::round(y1 / res);
    const double nx = std::round((x1 - x0) / res), ny = std::round((y1 - y0) / res);
    if (!(nx >= 0 && ny >= 0 && nx < 4e9 && ny < 4e9))
        return {UINT32_MAX, UINT32_MAX};
    return {uint64_t(nx), uint64_t(ny)};
}
}  // namespace grid_readers

namespace {
bool endsWith(std::string s, const std::string& suffix) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char ch) { return std::tolower(ch); });
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

using namespace grid_readers;

mrpt::maps::COccupancyGridMap2D loadOccupancyGrid(const TMapSourceOptions& src) {
    const std::string& f = src.map_file;
    if (const std::string why = fileProblem(f); !why.empty())
        throw CBadInputError(f + ": map file " + why);
    COccupancyGridMap2D g;
    if (endsWith(f, ".gridmap") || endsWith(f, ".gridmap.gz"))
        g = fromGridmap(f);
    else if (endsWith(f, ".yaml") || endsWith(f, ".yml"))
        g = fromRosYaml(f);
    else if (endsWith(f, ".simplemap") || endsWith(f, ".simplemap.gz"))
        g = fromSimplemap(f, src.simplemap_resolution, src.section);
    else
        g = fromImage(f, src.map_resolution, src.map_origin_x, src.map_origin_y,
                      TPixelModel::FreeIsWhite);
    if (g.getSizeX() < 2 || g.getSizeY() < 2)
        throw CBadInputError(f + ": the map is empty");
    return g;
}

void saveGridmapGz(const mrpt::maps::COccupancyGridMap2D& g, const std::string& path) {
    try {
        mrpt::io::CFileGZOutputStream f(path);
        auto a = mrpt::serialization::archiveFrom(f);
        a << g;
    } catch (const std::exception&) {
        // MRPT says only "Cannot write bytes to stream!": name the file.
        throw writeFailure(path, errno);
    }
}

}  // namespace risknav::common
