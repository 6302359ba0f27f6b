#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <cstdint>
#include <string>
#include <vector>

namespace risknav::speed {
/** The rules across the local map's and the memory's keys, the same in
 * [Explore] and in nav::CAdaptiveSpeedLimiter's section: at most 2000 local
 * cells and 4096 memory cells a side, a memory of 0 (none) or at least the
 * local map, its cell at most a quarter of the local map. Throws
 * CConfigKeyError naming `section`. */
void checkLocalMapSizes(const std::string& section, double localMapSize,
                        double localMapResolution, double memorySize,
                        double memoryResolution);

/** [Explore] of risknav-explore: the run, not the method. Every key, its
 * range and its doc are declared once, in declare() (TExploreOptions.cpp). */
struct TExploreOptions : public common::CDeclaredOptions {
    TExploreOptions() { section = "Explore"; }
    std::vector<double> start = {};         ///< x y heading_deg (world frame)
    std::vector<double> destinations = {};  ///< x y pairs, visited in order (world frame)
    /** Modes of one run: "adaptive" and / or "fixed" (one run per candidate
     * speed), compared in the outputs. */
    std::vector<std::string> modes = {"adaptive", "fixed"};
    /** How the robot knows its motion (moves its maps, places the
     * destinations): scan_matching (odometry corrected by aligning each
     * laser scan to the map the robot builds, CScanMatchLocalizer; beyond
     * the paper), odometry (alone: it drifts), or ground_truth. */
    std::string ego_motion = "scan_matching";
    double local_map_size = 10.0;        ///< [m] side of the robot-centred grids
    double local_map_resolution = 0.05;  ///< [m]
    /** [m] side of the coarse memory (CFreeSpaceMemory) that ranks the ways
     * on to a destination beyond the local map, at least: the runs grow it
     * to hold every destination with a local map to spare
     * (exploreMemorySize()); 0 = none (the paper's straight line). Beyond
     * the paper. */
    double memory_size = 50.0;
    double memory_resolution = 0.25;  ///< [m]
    double sim_dt = 0.05;             ///< [s] physics step inside a cycle
    double duration_max = 300;        ///< [s] simulated, per mode
    /** [m] a destination counts as reached when the robot's TRUE pose (the
     * simulator's ground truth) is within this where it believed it had
     * arrived (judgeArrival()). */
    double goal_tolerance = 0.3;
    /** [m] the robot believes it has arrived (and halts, and goes on) when
     * its believed pose is within this of the destination (or within
     * min(this, goal_tolerance / 2) of the point nearest it that it may come
     * to); at most goal_tolerance. Below it, so
     * that a small belief error does not by itself put the true pose out of
     * goal_tolerance: halting at the tolerance's edge in belief, the robot
     * was truly outside it about every other time. */
    double arrival_radius = 0.15;
    double unreachable_after = 5;
    /** [s] a destination the robot has not come 0.5 m nearer to (in the ego
     * frame) for this long is given up as unreachable (MRPT's reactive
     * navigator raises its "not approaching the target" alarm after 30 s;
     * exploring needs detours); 0 = never. Beyond the paper. */
    double not_approaching_timeout =
        90;  ///< [s] of "unreachable" before a destination is given up
    /** Turn once on the spot before setting off (beyond the paper: a laser
     * mounted ahead of the centre has not seen beside and behind the robot). */
    bool look_around = true;
    int max_snapshots = 40;  ///< snapshots/ of the adaptive mode (0 = none)
    uint64_t seed = 1;

  protected:
    void declare(Visitor& v) override;
    void validateRules() const override;
};
}  // namespace risknav::speed
