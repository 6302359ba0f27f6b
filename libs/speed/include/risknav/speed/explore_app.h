#pragma once
#include <risknav/common/CAppRunner.h>
#include <risknav/common/COutputDir.h>
#include <risknav/speed/CExplorer.h>

#include <nlohmann/json.hpp>

#include <vector>

namespace risknav::speed {
/** The figures of one mode in summary.json. */
nlohmann::json modeSummary(const TModeResult& r, const TSpeedControlOptions& o);

/** Writes cycles.csv, trace.png, speed_profile.png and snapshots/ of the runs. */
void writeExploreOutputs(const CExplorer& ex, const std::vector<TModeResult>& runs,
                         common::COutputDir& out);

/** risknav-explore's body: loads the config, runs every mode, writes the
 * outputs and summary.json. */
void runExploreApp(const common::TAppContext& ctx);
}  // namespace risknav::speed
