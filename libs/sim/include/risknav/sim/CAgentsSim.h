#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/sim/range_geometry.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <random>
#include <string>
#include <vector>

namespace risknav::sim {
/** Something that happened to an agent: "emerge" (a door pedestrian came
 * out), "spawn" (a corridor walker started), "leave" (reached the end of its
 * path), "give_up" (blocked by the robot longer than its patience). */
struct TAgentEvent {
    double t = 0;
    std::string kind, source, agent;
    double x = 0, y = 0;
};

/** The dynamic (and optional static) obstacles that are not in the map:
 *  - [DoorPedestrianN]: a person who emerges from a door (a segment on a
 *    wall) at 0.8 m/s by default, follows a path into and across the
 *    corridor, and leaves at its end. Emergence: poisson (rate_per_min),
 *    schedule (listed times) or trigger (when the robot comes within
 *    trigger_distance of the door, with trigger_probability).
 *  - [CorridorWalkerN]: people walking a polyline at a speed drawn from
 *    [speed_min, speed_max] (1.6-2.0 m/s), one every `period` seconds.
 *  - [ClutterN]: static discs (furniture the map does not know).
 * Agents never steer into the robot: they keep their paths and wait while the
 * next step would touch the robot (give up after `patience` s). */
class CAgentsSim {
  public:
    /** [DoorPedestrianN], [CorridorWalkerN], [ClutterN]: every key, its
     * range and doc declared once, in declare(); `section` names the one
     * read. */
    struct TDoorPedestrian : public common::CDeclaredOptions {
        TDoorPedestrian() { section = "DoorPedestrian1"; }
        double door[4] = {0, 0, 0, 0};           ///< x1 y1 x2 y2 [m]
        std::vector<mrpt::math::TPoint2D> path;  ///< from the doorway into the corridor
        double speed = 0.8, radius = 0.25, patience = 10.0;
        std::string emergence = "trigger";  ///< poisson | schedule | trigger
        double rate_per_min = 1.0;
        std::vector<double> schedule;
        double trigger_distance = 2.0, trigger_probability = 0.5;
        mrpt::math::TPoint2D doorMid() const {
            return {0.5 * (door[0] + door[2]), 0.5 * (door[1] + door[3])};
        }

      protected:
        void declare(Visitor& v) override;
        void validateRules() const override;
    };
    struct TWalker : public common::CDeclaredOptions {
        TWalker() { section = "CorridorWalker1"; }
        std::vector<mrpt::math::TPoint2D> path;
        double speed_min = 1.6, speed_max = 2.0, radius = 0.25, period = 30.0,
               phase = 0.0, patience = 10.0;

      protected:
        void declare(Visitor& v) override;
        void validateRules() const override;
    };
    struct TClutter : public common::CDeclaredOptions {
        TClutter() { section = "Clutter1"; }
        double x = 0, y = 0, radius = 0.3;

      protected:
        void declare(Visitor& v) override;
    };

    std::vector<TDoorPedestrian> doors;
    std::vector<TWalker> walkers;
    std::vector<TClutter> clutter;

    /** Reads (and validates) every [DoorPedestrianN], [CorridorWalkerN] and
     * [ClutterN] section. */
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c);
    /** Writes every person and clutter section back (config_effective.ini). */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** Section names this class owns (for unknown-section checks). */
    static bool ownsSection(const std::string& section);

    void reset(uint64_t seed);
    /** Advances all agents by dt (time t is the end of the step). */
    void step(double t, double dt, const mrpt::math::TPose2D& robot, double robotRadius,
              std::vector<TAgentEvent>& events);
    /** Discs of the active people and of the clutter; ids are stable per agent. */
    std::vector<TDisc> discs() const;
    /** The first clutter disc a disc of `radius` at (x, y) overlaps, with
     * the distance between the centres; nullptr: none (a start check). */
    const TClutter* clutterOverlapping(double x, double y, double radius,
                                       double* centreDistance = nullptr) const;
    /** Name ("DoorPedestrian2#3") of the person with this disc id. */
    const std::string& agentName(int id) const { return m_names.at(size_t(id)); }

  private:
    struct TActive {
        std::string name, source;
        const std::vector<mrpt::math::TPoint2D>* path;
        size_t seg = 0;
        double along = 0, speed = 0, radius = 0, blocked = 0, patience = 0;
        double x = 0, y = 0;
        int id = 0;
        int doorIndex = -1;
    };
    void spawn(double t, const std::string& kind, const std::string& source,
               size_t srcIdx, int doorIndex,
               const std::vector<mrpt::math::TPoint2D>& path, double speed, double radius,
               double patience, std::vector<TAgentEvent>& events);
    std::vector<TActive> m_active;
    std::vector<double> m_nextTime;   // per door (poisson)
    std::vector<size_t> m_nextSched;  // per door (schedule)
    std::vector<bool> m_armed;        // per door (trigger)
    std::vector<double> m_nextWalker;
    std::vector<int> m_counts;  // people spawned per door/walker source
    int m_nextId = 0;
    std::vector<std::string> m_names;  // by agent id
    std::mt19937_64 m_rng;
};

}  // namespace risknav::sim
