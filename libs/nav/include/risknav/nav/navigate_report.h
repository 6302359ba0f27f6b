#pragma once
#include <risknav/common/COutputDir.h>
#include <risknav/nav/CNavigationRun.h>

#include <nlohmann/json.hpp>

#include <string>

namespace risknav::nav {
/** cycles.csv: one row per navigation cycle (TNavCycle). */
void writeCyclesCsv(const TNavRunResult& r, double startTime, const std::string& path);
/** events.csv: the navigator's events, tagged waypoints, people's events and
 * collisions / near misses, by time. */
void writeEventsCsv(const TNavRunResult& r, double startTime, const std::string& path);
/** trajectory.png: the map, the path coloured by speed (colour bar in m/s),
 * waypoints, people's tracks, events, collisions, the afraid zones when a
 * CAfraidSpeedLimiter level is given (cells above its threshold). */
void drawTrajectory(const CNavigationRun& run, const TNavRunResult& r,
                    const std::string& title, const std::string& path,
                    const std::vector<uint8_t>* zoneMask = nullptr);
/** speed_profile.png: actual speed and the limit vs distance [m], the speed
 * coloured by the limiter that won each cycle. */
void drawSpeedProfile(const TNavRunResult& r, const std::string& title,
                      const std::string& path);
/** The summary.json keys of one run (README "risknav-navigate"). */
nlohmann::json runSummary(const CNavigationRun& run, const TNavRunResult& r);

}  // namespace risknav::nav
