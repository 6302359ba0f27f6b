#pragma once
#include <risknav/common/CAppRunner.h>
#include <risknav/common/COutputDir.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <nlohmann/json.hpp>

#include <string>

namespace risknav::common {
/** The keys every summary.json starts with: app, risknav_version,
 * mrpt_version, config (absolute path), seed, plus "overrides" (the --set list). */
nlohmann::json summaryHeader(const TAppContext& ctx, uint64_t seed);

/** The end of an app's run: writes config_effective.ini (from the keys the
 * options saved into `effective`), lists every staged file and summary.json
 * in summary["outputs"], writes summary.json and commits the folder. */
void commitRun(const TAppContext& ctx, COutputDir& out, nlohmann::json& summary,
               const mrpt::config::CConfigFileMemory& effective);

/** Pretty-printed JSON (2 spaces, trailing newline). Non-finite doubles are
 * written as null by nlohmann::json; callers avoid them. */
std::string jsonText(const nlohmann::json& j);

}  // namespace risknav::common
