#pragma once
// The map file readers behind loadOccupancyGrid() (grid_io.h), one file a
// family of formats: grid_image_io.cpp (images, ROS map_server YAML),
// grid_mrpt_io.cpp (MRPT's .gridmap and .simplemap); the limits they share
// are in grid_io.cpp. Private to risknav::common.
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <cstdint>
#include <string>
#include <utility>

namespace risknav::common::grid_readers {

enum class TPixelModel {
    FreeIsWhite,  // P(free) = grey/255 (MRPT bitmaps)
    RosTrinary,
    RosScale
};

struct TRosParams {
    double occupied = 0.65, free = 0.196;
    bool negate = false;
};

// The largest grid risknav reads (cells): 25 M, e.g. 250 m x 250 m at 5 cm.
constexpr uint64_t kMaxGridCells = 25'000'000;

/** "N M cells", for messages. */
std::string cellsText(uint64_t n);

/** The cells COccupancyGridMap2D::setSize would allocate for these bounds:
 * the same float arithmetic as MRPT 2.5's (bounds rounded to the
 * resolution, then round(span / res) a side), so that it is known BEFORE
 * MRPT allocates. {0, 0} for bounds MRPT would refuse. */
std::pair<uint64_t, uint64_t> setSizeCells(float x0, float x1, float y0, float y1,
                                           float res);

/** A bitmap (PNG, BMP, PGM, ...) of `res` metres a pixel, its lower-left
 * corner at (ox, oy), read with the pixel model given. */
mrpt::maps::COccupancyGridMap2D fromImage(const std::string& file, double res, double ox,
                                          double oy, TPixelModel model,
                                          const TRosParams& ros = {});
/** ROS map_server's YAML and the image it names. */
mrpt::maps::COccupancyGridMap2D fromRosYaml(const std::string& file);
/** MRPT's serialized COccupancyGridMap2D (.gridmap, .gridmap.gz). */
mrpt::maps::COccupancyGridMap2D fromGridmap(const std::string& file);
/** MRPT's CSimpleMap (.simplemap, .simplemap.gz): the grid of its 2D scans. */
mrpt::maps::COccupancyGridMap2D fromSimplemap(const std::string& file, double res,
                                              const std::string& section);
}  // namespace risknav::common::grid_readers
