#pragma once
#include <mrpt/maps/COccupancyGridMap2D.h>

#include <cstdint>
#include <string>
#include <vector>

namespace risknav::afraid {
/** Accumulated experience (Choi, Chung, Song (002) eq. 12), on the geometry
 * of the map: per cell, how many afraid events happened with the robot there,
 * how many unexpected obstacles were seen there, and how often the robot was
 * there at all (exposure, in frames), so that rates and not raw counts are
 * compared. Saved as a versioned gz file (.afraid) that later runs load and
 * add to. */
class CAfraidGrid {
  public:
    static constexpr uint32_t kVersion = 1;

    CAfraidGrid() = default;
    /** An empty grid on the geometry of the map. */
    explicit CAfraidGrid(const mrpt::maps::COccupancyGridMap2D& map);

    bool sameGeometry(const CAfraidGrid& o) const;
    std::string geometryText() const;

    void addExposure(double x, double y);
    void addRobotEvent(double x, double y);
    void addObstacleEvent(double x, double y);
    /** Adds another grid's counts (learning is resumable); throws
     * std::runtime_error if the geometry differs. */
    void merge(const CAfraidGrid& other);

    /** Atomic write: temporary file + rename. */
    void save(const std::string& path) const;
    /** Throws std::runtime_error (naming the file and what is wrong) on a
     * missing, unreadable, truncated, foreign or newer-version file. */
    static CAfraidGrid load(const std::string& path);

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
    uint64_t totalRobotEvents() const;
    uint32_t runs = 0;    ///< learning runs (rawlogs) accumulated
    uint64_t frames = 0;  ///< frames accumulated

  private:
    size_t index(double x, double y, bool& ok) const;
    double m_xmin = 0, m_ymin = 0, m_res = 0.05;
    int m_sx = 0, m_sy = 0;
    std::vector<uint32_t> m_exposure, m_robotEvents, m_obstacleEvents;
};

}  // namespace risknav::afraid
