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

std::string jsonText(const nlohmann::json& j) {
    return j.dump(2) + "\n";
}

}  // namespace risknav::common
