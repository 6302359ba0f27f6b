#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <string>

namespace risknav::common {
/** Where a static occupancy map comes from; the `map_*` keys of any app
 * section (`section`: the host section, for messages). PNG/PGM bitmaps need
 * resolution and origin; the other formats carry their own. Every key, its
 * range and its doc are declared once, in declare(). */
struct TMapSourceOptions : public CDeclaredOptions {
    TMapSourceOptions() { section = "World"; }
    std::string map_file;  ///< .png/.pgm/.bmp, .gridmap(.gz), .yaml (ROS map_server),
                           ///< .simplemap(.gz)
    double map_resolution = 0.05;  ///< [m/px] bitmaps only
    double map_origin_x =
        0.0;  ///< [m] world x of the bitmap's lower-left corner (ROS convention)
    double map_origin_y = 0.0;  ///< [m] world y of the bitmap's lower-left corner
    double simplemap_resolution =
        0.05;  ///< [m] cell size when building a grid from a .simplemap

  protected:
    void declare(Visitor& v) override;
    /** map_file is required. */
    void validateRules() const override;
};

/** Loads a grid. Bitmaps: P(free) = grey/255 (white free, black occupied),
 * row 0 of the image is the top (max y). ROS YAML: image, resolution,
 * origin [x, y, yaw=0], negate, occupied_thresh, free_thresh, mode
 * (trinary|scale). .simplemap: a grid is built by inserting every keyframe's
 * scans. Throws CBadInputError naming the file on any problem (missing,
 * unreadable, wrong format, empty map). */
mrpt::maps::COccupancyGridMap2D loadOccupancyGrid(const TMapSourceOptions& src);

/** Writes a grid as MRPT's .gridmap.gz (gz-compressed serialized object), the
 * format pf-localization reads. */
void saveGridmapGz(const mrpt::maps::COccupancyGridMap2D& g, const std::string& path);

}  // namespace risknav::common
