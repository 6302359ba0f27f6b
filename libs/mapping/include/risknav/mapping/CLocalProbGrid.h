#pragma once
#include <risknav/mapping/TSensorModel.h>

#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <cstdint>
#include <vector>

namespace risknav::mapping {
/** The class of a cell of one sensor's local grid ((000) section 2). */
enum class TCellClass : uint8_t {
    Obstacle,             ///< P > occupied threshold (0.7)
    Free,                 ///< P < free threshold (0.2)
    UndecidedObserved,    ///< between, observed at least once
    UndecidedUnobserved,  ///< never observed
};

/** A robot-centred probabilistic grid of one sensor (Miura et al. (000)
 * section 2): P(E) per cell (prior 0.5) and the number of observations, in
 * the ego-motion frame (odometry or ground truth), kept centred on the robot.
 *
 * Beyond the paper: the paper rotates and shifts the grid by the ego-motion
 * before every update; resampling a grid every cycle moves its content by up
 * to half a cell each time, and the errors add up (a wall drifts and blurs).
 * This grid keeps the axes of the ego frame and scrolls by whole cells when
 * the robot moves (recenter), which is exact; the robot's heading is a pose in
 * the grid, not a rotation of it. Planning happens in the same frame.
 *
 * Why not MRPT's COccupancyGridMap2D: it stores 8-bit log-odds (a weak
 * stereo-like update of ln 0.73 is quantized), keeps no observation count and
 * cannot scroll its cells; images and snapshots still go through MRPT grids
 * (toMrptGrid in free_space.h). */
class CLocalProbGrid {
  public:
    /** Beyond the paper: P is kept in [0.05, 0.95]. Unclamped, a cell read
     * free a hundred times needs dozens of occupied readings before it turns
     * into an obstacle (and float P reaches 0, after which no reading can
     * move it); clamped, a laser-like model (0.7 / 0.3) marks a newly placed
     * object within 5 readings. N (0.5 -> below 0.2) is not affected. */
    static constexpr double kProbabilityMin = 0.05;

    CLocalProbGrid() = default;
    /** size x size cells of `resolution` m, centred on (cx, cy). */
    CLocalProbGrid(int size, double resolution, double cx = 0, double cy = 0);

    int size() const { return m_n; }
    double resolution() const { return m_res; }
    /** Ego-frame position of the corner of cell (0, 0). */
    double xMin() const { return m_x0; }
    double yMin() const { return m_y0; }
    int x2idx(double x) const;
    int y2idx(double y) const;
    double idx2x(int i) const { return m_x0 + (i + 0.5) * m_res; }
    double idx2y(int j) const { return m_y0 + (j + 0.5) * m_res; }
    bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < m_n && j < m_n; }
    size_t index(int i, int j) const { return size_t(j) * m_n + i; }

    /** Scrolls the grid by whole cells so that (x, y) lies in the centre cell;
     * cells that come in are unknown (P = 0.5, no observations). Returns the
     * shift in cells (di, dj) the content moved by. */
    std::pair<int, int> recenter(double x, double y);

    /** One scan taken at `robot` (ego frame; the sensor pose inside the scan
     * is applied), the sector model of (000) Fig. 4: every cell within the
     * sensor's field of view and range, whose bearing falls in a ray's angular
     * sector, gets one reading per scan: free when nearer than R_min =
     * R - delta(R), occupied within [R_min, R_max], none beyond R_max. A ray
     * without a return (invalid) reads free up to maxRange. Each cell read
     * counts one observation. */
    void integrateScan(const mrpt::math::TPose2D& robot,
                       const mrpt::obs::CObservation2DRangeScan& scan,
                       const TSensorModel& m);

    float probability(int i, int j) const { return m_p[index(i, j)]; }
    uint16_t observations(int i, int j) const { return m_count[index(i, j)]; }
    const std::vector<float>& probabilities() const { return m_p; }
    const std::vector<uint16_t>& counts() const { return m_count; }
    /** Sets one cell (tests, and loading). */
    void setCell(int i, int j, float p, uint16_t count);

  private:
    int m_n = 0;
    double m_res = 0.05;
    double m_x0 = 0, m_y0 = 0;
    std::vector<float> m_p;
    std::vector<uint16_t> m_count;
    std::vector<float> m_pSpare;  // recenter()'s buffers
    std::vector<uint16_t> m_countSpare;
    // integrateScan's per-ray tables, kept to spare the allocations
    std::vector<uint8_t> m_rayValid;
    std::vector<double> m_rayFree, m_rayOcc;
    std::vector<double> m_boundX, m_boundY;  ///< the sectors' edge directions
};

/** Classification of (000) section 2: P > occupied: obstacle; P < free: free;
 * else undecided, with or without observation. */
inline TCellClass classifyCell(float p, uint16_t observations, double occupiedThreshold,
                               double freeThreshold) {
    if (p > occupiedThreshold)
        return TCellClass::Obstacle;
    if (p < freeThreshold)
        return TCellClass::Free;
    return observations > 0 ? TCellClass::UndecidedObserved
                            : TCellClass::UndecidedUnobserved;
}
}  // namespace risknav::mapping
