#pragma once
#include <optional>
#include <string>

namespace risknav::common {
/** Config names that were renamed so that the same thing has the same name
 * in every app (the start pose, the time limit, the stopping rule's
 * section). A config that still uses an old name is refused with a line
 * naming the new one, never read under the old name.
 *
 * The new name of section `section` (case-insensitive), if it was renamed. */
std::optional<std::string> renamedSection(const std::string& section);

/** The new "[section] key" of key `key` in section `section`
 * (case-insensitive), if it was renamed. */
std::optional<std::string> renamedKey(const std::string& section, const std::string& key);
}  // namespace risknav::common
