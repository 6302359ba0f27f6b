#pragma once
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <cstdint>
#include <string>
#include <vector>

namespace risknav::afraid {
/** Accumulated experience (Choi, Chung, Song (002) eq. 12), on the geometry
 * of the map: per cell, how many afraid events happened with the robot there,
 * how many unexpected obstacles were seen there (projected onto the robot's
 * path), how often the robot entered the cell (passes) and how many frames it
 * spent there (exposure), so that rates per pass and not raw counts are
 * compared: a robot that stands or crawls does not dilute the rate, and more
 * laps of the same world give the same rate. Saved as a versioned gz file (.afraid) that
 * later runs load and add to.
 *
 * The .afraid format (gzip-compressed; every number LITTLE-ENDIAN, written and
 * read byte by byte whatever the host's byte order; doubles are IEEE-754
 * binary64 with their 64 bits in little-endian order; no padding):
 *
 *   offset  size  field
 *        0     8  magic "RNAFRAID"
 *        8     4  u32 version (kVersion = 3; versions 1 and 2 are still read)
 *       12    24  f64 x_min, f64 y_min [m], f64 resolution [m] (finite, > 0)
 *       36     8  i32 size_x, i32 size_y [cells] (> 0, product <= kMaxCells)
 *       44     4  u32 runs
 *       48     8  u64 frames
 *       56        four sparse layers, in this order: exposure (frames), robot
 *                 events, obstacle events, passes (version 3 only); each one
 *                 u32 n (<= cells) followed by n pairs (u32 cell index =
 *                 cy * size_x + cx, u32 count)
 *
 * Version 3 (this build writes it): the layout above, explicitly
 * little-endian; cell indices strictly increasing, counts > 0, nothing after
 * the last layer. Version 2: the same without the passes layer; its frames
 * are taken as passes (at the learning speeds the robot enters about one
 * cell per frame). Version 1 (risknav before the explicit byte order): the
 * same layout, each field's memory written as is, i.e. in the writer's HOST
 * byte order; it is read as little-endian, the order of the hosts risknav
 * runs on (x86-64, arm64); a version 1 file from a big-endian host would be
 * refused (geometry) or misread. Version 1's leniency stays: any index order,
 * trailing bytes ignored.
 *
 * Bounds, checked before anything is allocated: a grid holds at most
 * kMaxCells cells (the dense layers of a grid that large take 12 bytes per
 * cell, 300 MB); a layer's n must fit in the bytes that are left of the
 * decompressed file; the decompressed file may not be longer than its header
 * allows (a gz bomb is not inflated past that). */
class CAfraidGrid {
  public:
    static constexpr uint32_t kVersion = 3;
    /** Oldest version load() still reads. */
    static constexpr uint32_t kOldestVersion = 1;
    /** The largest grid, in cells (e.g. 5000 x 5000 cells: 250 m x 250 m at
     * 5 cm); a .afraid header claiming more is refused, and so is a map larger
     * than this. */
    static constexpr uint64_t kMaxCells = 25'000'000;

    CAfraidGrid() = default;
    /** An empty grid on the geometry of the map; throws
     * common::CBadInputError if the map has more than kMaxCells cells. */
    explicit CAfraidGrid(const mrpt::maps::COccupancyGridMap2D& map);

    bool sameGeometry(const CAfraidGrid& o) const;
    std::string geometryText() const;

    /** The robot was at (x, y) [m] (one count of exposure). */
    void addExposure(double x, double y);
    /** The robot moved from (x0, y0) to (x1, y1): one pass of each cell it
     * entered on the way (standing still adds nothing). */
    void addTraversal(double x0, double y0, double x1, double y1);
    /** One pass of the cell at (x, y) (where a run starts). */
    void addPass(double x, double y);
    /** An afraid event (eq. 11) with the robot at (x, y): eq. (12) counted at
     * the robot's cell. */
    void addRobotEvent(double x, double y);
    /** The unexpected obstacle of an event was at (x, y): eq. (12) counted at
     * the obstacle's cell (the paper's Fig. 8 counts along the corridor). */
    void addObstacleEvent(double x, double y);
    /** Adds another grid's counts (learning is resumable); throws
     * std::runtime_error if the geometry differs. */
    void merge(const CAfraidGrid& other);

    /** Atomic write (temporary file + rename) of encode(), gz-compressed. */
    void save(const std::string& path) const;
    /** Throws common::CBadInputError (one line, naming the file and what is
     * wrong) on a missing, unreadable, truncated, foreign, corrupt, too large
     * or newer-version file. Reads versions kOldestVersion..kVersion. */
    static CAfraidGrid load(const std::string& path);

    /** The uncompressed .afraid content (current version, little-endian). */
    std::string encode() const;
    /** Parses uncompressed .afraid content (any readable version); `name`
     * (the file) starts every error message. Throws common::CBadInputError. */
    static CAfraidGrid decode(const std::string& bytes, const std::string& name);

    int sizeX() const { return m_sx; }
    int sizeY() const { return m_sy; }
    double xMin() const { return m_xmin; }
    double yMin() const { return m_ymin; }
    double resolution() const { return m_res; }
    bool inside(int cx, int cy) const {
        return cx >= 0 && cy >= 0 && cx < m_sx && cy < m_sy;
    }
    int xToCol(double x) const;
    int yToRow(double y) const;
    double colToX(int cx) const { return m_xmin + (cx + 0.5) * m_res; }
    double rowToY(int cy) const { return m_ymin + (cy + 0.5) * m_res; }

    const std::vector<uint32_t>& exposure() const { return m_exposure; }
    const std::vector<uint32_t>& robotEvents() const { return m_robotEvents; }
    const std::vector<uint32_t>& obstacleEvents() const { return m_obstacleEvents; }
    const std::vector<uint32_t>& passes() const { return m_passes; }
    uint64_t totalRobotEvents() const;
    uint32_t runs = 0;    ///< learning runs (rawlogs) accumulated
    uint64_t frames = 0;  ///< frames accumulated

  private:
    size_t index(double x, double y, bool& ok) const;
    double m_xmin = 0, m_ymin = 0, m_res = 0.05;
    int m_sx = 0, m_sy = 0;
    std::vector<uint32_t> m_exposure, m_robotEvents, m_obstacleEvents, m_passes;
};

}  // namespace risknav::afraid
