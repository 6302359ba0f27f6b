#pragma once
#include <risknav/sim/CAgentsSim.h>

#include <mrpt/math/TPose2D.h>

#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace risknav::sim {
/** A collision or near-miss episode (one event per episode, not per step). */
struct TSafetyEvent {
    double t = 0;
    std::string kind;    ///< collision | near_miss
    std::string object;  ///< the person's name, the clutter section, or "map"
    double rx = 0, ry = 0, ox = 0, oy = 0;
    double gap = 0;  ///< robot edge to object edge [m]
};

/** Watches the robot's distance to people, clutter and the map after every
 * step: episodes of collision (gap < 0) and near miss (gap < near_miss_distance),
 * and the smallest gaps. An episode ends when the gap opens again beyond the
 * near-miss distance (+5 cm hysteresis). */
class CSafetyMonitor {
  public:
    double near_miss_distance = 0.2;  ///< [m]

    void reset();
    /** After a step ending at time t: the robot (disc of radius robotRadius) at
     * pose, the people and clutter, the robot's clearance to the map [m]. */
    void update(double t, const mrpt::math::TPose2D& pose, double robotRadius,
                const CAgentsSim& agents, double mapClearance);

    /** Door pedestrians entering the robot's stopping corridor while it moves:
     * part of a person's disc inside the rectangle ahead of the robot that is
     * halfWidth to each side and reaches `reach` beyond the robot's front,
     * with the robot faster than minSpeed. One `enter_corridor` event per
     * person (the emergences an afraid detector should catch: "relevant"). */
    void updateCorridor(double t, const mrpt::math::TPose2D& pose, double speed,
                        double robotRadius, double reach, double halfWidth,
                        const CAgentsSim& agents, double minSpeed = 0.05);

    const std::vector<TSafetyEvent>& events() const { return m_events; }
    const std::vector<TAgentEvent>& corridorEntries() const { return m_entries; }
    int collisions() const { return m_collisions; }  ///< with people and clutter
    int collisionsStatic() const { return m_collisionsStatic; }  ///< with the map
    int nearMisses() const { return m_nearMisses; }
    /** Smallest gaps [m]; +inf when nothing was ever near. */
    double minGapAgents() const { return m_minGapAgents; }
    double minGapStatic() const { return m_minGapStatic; }

  private:
    std::vector<TSafetyEvent> m_events;
    std::vector<TAgentEvent> m_entries;
    std::set<int> m_entered;       // agent ids already in m_entries
    std::map<int, int> m_contact;  // object id -> 0 clear, 1 near, 2 collision
    int m_staticState = 0;
    int m_collisions = 0, m_collisionsStatic = 0, m_nearMisses = 0;
    double m_minGapAgents = std::numeric_limits<double>::infinity();
    double m_minGapStatic = std::numeric_limits<double>::infinity();
};

}  // namespace risknav::sim
