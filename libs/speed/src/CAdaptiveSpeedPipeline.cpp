#include <risknav/speed/CAdaptiveSpeedPipeline.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;

namespace risknav::speed {
void markFootprintFree(mapping::TFreeSpaceMap& m, const TPose2D& p, double radius) {
    const int r = int(std::ceil(radius / m.resolution));
    const int ci = m.x2idx(p.x), cj = m.y2idx(p.y);
    for (int j = cj - r; j <= cj + r; j++)
        for (int i = ci - r; i <= ci + r; i++)
            if (m.inside(i, j) &&
                std::hypot(m.idx2x(i) - p.x, m.idx2y(j) - p.y) <= radius &&
                m.cells[m.index(i, j)] == mapping::TFusedCell::Undecided)
                m.cells[m.index(i, j)] = mapping::TFusedCell::Free;
}

int CAdaptiveSpeedPipeline::necessaryObservations(const TParams& p) {
    int n = mapping::necessaryObservations(p.laserModel, p.speed.free_threshold);
    if (p.useRange2)
        n = std::max(
            n, mapping::necessaryObservations(p.range2Model, p.speed.free_threshold));
    return n;
}

namespace {
int cellsPerSide(const CAdaptiveSpeedPipeline::TParams& p) {
    if (!(p.localMapResolution > 0) || !(p.localMapSize >= 2 * p.localMapResolution))
        throw std::invalid_argument(
            "adaptive speed pipeline: local map size and resolution must be > 0");
    return int(std::lround(p.localMapSize / p.localMapResolution));
}
}  // namespace

CAdaptiveSpeedPipeline::CAdaptiveSpeedPipeline(const TParams& p, const TPose2D& ego0)
    : m_p(p),
      m_ctrl(p.speed, p.robotRadius, necessaryObservations(p)),
      m_laser(cellsPerSide(p), p.localMapResolution, ego0.x, ego0.y),
      m_range2(cellsPerSide(p), p.localMapResolution, ego0.x, ego0.y) {
    if (p.memorySize > 0)
        m_memory = std::make_unique<mapping::CFreeSpaceMemory>(
            p.memorySize, p.memoryResolution, ego0.x, ego0.y);
}

void CAdaptiveSpeedPipeline::update(const TPose2D& ego,
                                    const mrpt::obs::CObservation2DRangeScan* laser,
                                    const TPose2D& laserPose,
                                    const mrpt::obs::CObservation2DRangeScan* range2,
                                    const TPose2D& range2Pose) {
    // (000) section 2: the grids follow the ego-motion, then take the scans
    // (each sensor's grid its own part)
    common::parallelFor(m_parallel, 2, [&](size_t s) {
        mapping::CLocalProbGrid& g = s == 0 ? m_laser : m_range2;
        const mrpt::obs::CObservation2DRangeScan* scan = s == 0 ? laser : range2;
        g.recenter(ego.x, ego.y);
        if (scan)
            g.integrateScan(s == 0 ? laserPose : range2Pose, *scan,
                            s == 0 ? m_p.laserModel : m_p.range2Model);
    });
    // classification and two-sensor fusion (section 2)
    m_fused = mapping::fuseGrids(m_laser, m_p.useRange2 ? m_range2 : m_laser,
                                 m_p.speed.occupied_threshold, m_p.speed.free_threshold);
    // Beyond the paper: the robot's own footprint is free (it stands
    // there), though no sensor sees under it (the laser is mounted ahead
    // of the centre); otherwise the robot would start in "unknown" space.
    markFootprintFree(m_fused, ego, m_p.robotRadius);
    // the clearance is read only against the widest inflation (the fastest
    // speed's margin) and, by CExplorer and the limiter's guide point, the
    // radius + 0.1 m and the radius: 0.5 m beyond the widest covers them all
    // the field and the memory's update both only read the fused map
    common::parallelFor(m_parallel, 2, [&](size_t part) {
        if (part == 0)
            m_field = computePlanningField(
                m_fused, m_p.robotRadius, m_ctrl.wayOnBand(m_p.localMapResolution),
                m_p.robotRadius + m_p.speed.margins.front() + 0.5, m_parallel,
                m_wayOnAhead);
        else if (m_memory)
            m_memory->update(m_fused);
    });
}

TSpeedDecision CAdaptiveSpeedPipeline::decide(
    const TPose2D& ego, const TPoint2D& goal, int fixedIndex,
    const std::optional<TPoint2D>& previousTarget) {
    // the memory's cost to the destination, computed when a temporary
    // destination is to be chosen, at most once a cycle
    if (m_field.map.cells.empty())
        throw std::logic_error(
            "adaptive speed pipeline: decide() without a field (call "
            "update() first; takeField() took the last one)");
    bool costReady = false;
    TTargetHints hints;
    hints.previous = previousTarget;
    if (m_memory)
        hints.goalCost = [&](double x, double y) {
            if (!costReady) {
                m_memory->computeCostToGoal(goal, m_p.speed.frontier_goal_weight, m_fused,
                                            m_p.robotRadius);
                costReady = true;
            }
            // from a candidate (within the target band of a frontier or
            // the map's edge) to the unknown beyond
            return m_memory->costToGoal(
                x, y,
                m_p.robotRadius + m_p.speed.margins.back() + 3 * m_p.localMapResolution);
        };
    TSpeedDecision d = m_ctrl.decide(m_field, ego, goal, fixedIndex, hints);
    // the ways on next cycle beside the clearance when this cycle chose a
    // target other than the goal (then likely again), else only if asked
    m_wayOnAhead = d.reason == TSpeedReason::Unreachable || d.temporaryTarget ||
                   d.target.x != goal.x || d.target.y != goal.y;
    return d;
}

void CAdaptiveSpeedPipeline::setCycleTime(double T) {
    if (T == m_p.speed.cycle_time)
        return;
    if (!(T > 0 && T <= 10))
        throw std::invalid_argument(
            "adaptive speed pipeline: cycle time must be in (0, 10] s");
    m_p.speed.cycle_time = T;
    m_ctrl =
        CAdaptiveSpeedController(m_p.speed, m_p.robotRadius, necessaryObservations(m_p));
    m_ctrl.setParallelFor(m_parallel);
}

void CAdaptiveSpeedPipeline::setParallelFor(common::TParallelFor parallel) {
    m_parallel = std::move(parallel);
    m_ctrl.setParallelFor(m_parallel);
}

bool CAdaptiveSpeedPipeline::heldLongEnough(bool held) {
    if (!held) {
        m_held = 0;
        return false;
    }
    return ++m_held >= m_ctrl.necessaryObservations();
}
}  // namespace risknav::speed
