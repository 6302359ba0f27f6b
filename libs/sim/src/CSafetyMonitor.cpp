#include <risknav/sim/CSafetyMonitor.h>

#include <cmath>

namespace risknav::sim {
void CSafetyMonitor::reset() {
    const double nearMiss = near_miss_distance;
    *this = CSafetyMonitor();
    near_miss_distance = nearMiss;
}

void CSafetyMonitor::update(double t, const mrpt::math::TPose2D& now, double robotRadius,
                            const CAgentsSim& agents, double mapClearance) {
    for (const auto& d : agents.discs()) {
        const double gap = std::hypot(d.x - now.x, d.y - now.y) - d.r - robotRadius;
        m_minGapAgents = std::min(m_minGapAgents, gap);
        int& st = m_contact[d.objectId];
        const int nst = gap < 0 ? 2 : (gap < near_miss_distance ? 1 : 0);
        if (nst > st) {
            const std::string obj = d.objectId < 0
                                        ? agents.clutter[size_t(-1 - d.objectId)].section
                                        : agents.agentName(d.objectId);
            m_events.push_back({t, nst == 2 ? "collision" : "near_miss", obj, now.x,
                                now.y, d.x, d.y, gap});
            (nst == 2 ? m_collisions : m_nearMisses)++;
        }
        if (nst > st || gap > near_miss_distance + 0.05)
            st = nst;
    }
    const double gapStatic = mapClearance - robotRadius;
    m_minGapStatic = std::min(m_minGapStatic, gapStatic);
    if (gapStatic < 0 && m_staticState == 0) {
        m_events.push_back(
            {t, "collision", "map", now.x, now.y, now.x, now.y, gapStatic});
        m_collisionsStatic++;
    }
    m_staticState = gapStatic < 0;
}

void CSafetyMonitor::updateCorridor(double t, const mrpt::math::TPose2D& pose,
                                    double speed, double robotRadius, double reach,
                                    double halfWidth, const CAgentsSim& agents,
                                    double minSpeed) {
    if (speed <= minSpeed)
        return;
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    for (const auto& d : agents.discs()) {
        if (d.objectId < 0 || m_entered.count(d.objectId))
            continue;
        const std::string& name = agents.agentName(d.objectId);
        if (name.rfind("DoorPedestrian", 0) != 0)
            continue;
        // The person's centre in the robot frame.
        const double dx = d.x - pose.x, dy = d.y - pose.y;
        const double xr = c * dx + s * dy, yr = -s * dx + c * dy;
        if (xr + d.r > 0 && xr - d.r < robotRadius + reach &&
            std::abs(yr) - d.r <= halfWidth) {
            m_entered.insert(d.objectId);
            m_entries.push_back(
                {t, "enter_corridor", name.substr(0, name.find('#')), name, d.x, d.y});
        }
    }
}

}  // namespace risknav::sim
