#pragma once
#include <risknav/common/CAppRunner.h>

#include <nlohmann/json.hpp>

#include <string>

namespace risknav::common {
/** The keys every summary.json starts with: app, risknav_version,
 * mrpt_version, config (absolute path), seed, plus "overrides" (the --set list). */
nlohmann::json summaryHeader(const TAppContext& ctx, uint64_t seed);

/** Pretty-printed JSON (2 spaces, trailing newline). Non-finite doubles are
 * written as null by nlohmann::json; callers avoid them. */
std::string jsonText(const nlohmann::json& j);

}  // namespace risknav::common
