#include <risknav/common/config_read.h>
#include <risknav/common/renamed_keys.h>

#include <array>

namespace risknav::common {
namespace {
struct TRename {
    const char *section, *key, *newSection, *newKey;
};
// section, key (nullptr: the whole section), new section, new key
constexpr std::array<TRename, 6> kRenames{{
    {"stoppingrule", nullptr, "CStoppingDistanceLimiter", nullptr},
    {"explore", "time_limit", "Explore", "duration_max"},
    {"viewpointplan", "start_x", "ViewpointPlan", "start = x y"},
    {"viewpointplan", "start_y", "ViewpointPlan", "start = x y"},
    {"viewpointplan", "goal_x", "ViewpointPlan", "goal = x y"},
    {"viewpointplan", "goal_y", "ViewpointPlan", "goal = x y"},
}};
}  // namespace

std::optional<std::string> renamedSection(const std::string& section) {
    const std::string s = lowerCase(section);
    for (const auto& r : kRenames)
        if (!r.key && s == r.section)
            return std::string(r.newSection);
    return std::nullopt;
}

std::optional<std::string> renamedKey(const std::string& section,
                                      const std::string& key) {
    const std::string s = lowerCase(section), k = lowerCase(key);
    for (const auto& r : kRenames)
        if (r.key && s == r.section && k == r.key)
            return "[" + std::string(r.newSection) + "] " + r.newKey;
    return std::nullopt;
}
}  // namespace risknav::common
