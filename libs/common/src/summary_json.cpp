#include <risknav/common/config_read.h>
#include <risknav/common/summary_json.h>
#include <risknav/common/version.h>

#include <mrpt/version.h>

#include <filesystem>

namespace risknav::common {
nlohmann::json summaryHeader(const TAppContext& ctx, uint64_t seed) {
    nlohmann::json j;
    j["app"] = ctx.info.name;
    j["risknav_version"] = RISKNAV_VERSION_STR;
    j["mrpt_version"] = MRPT_version_str;
    j["config"] = std::filesystem::absolute(ctx.cfg.path()).lexically_normal().string();
    j["overrides"] = ctx.args.sets;
    j["seed"] = seed;
    return j;
}

void commitRun(const TAppContext& ctx, COutputDir& out, nlohmann::json& summary,
               const mrpt::config::CConfigFileMemory& effective) {
    out.writeText("config_effective.ini", effectiveConfigText(ctx.cfg.path(), effective));
    summary["outputs"] = out.stagedNames();
    summary["outputs"].push_back("summary.json");
    out.writeText("summary.json", jsonText(summary));
    out.commit();
}

std::string jsonText(const nlohmann::json& j) {
    // Text from configs and files (a route name, a file name, a sensor label)
    // may not be UTF-8: such bytes become U+FFFD instead of an exception that
    // would lose the run's results.
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace risknav::common
