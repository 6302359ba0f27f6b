#pragma once
#include <mrpt/config/CConfigFile.h>

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace risknav::common {
/** An MRPT .ini file (with MRPT's @define / ${VAR} / $eval{} preprocessor and
 * `//` comments) that remembers which keys were read, so that unknown keys
 * (typos) can be reported, and knows its own folder, so that relative paths
 * resolve against it. Never writes back to disk.
 *
 * All reads of the MRPT macros (MRPT_LOAD_CONFIG_VAR...) go through the
 * overridden readString(), so key tracking also covers MRPT's own options
 * structs loaded from this file. */
class CIniConfig : public mrpt::config::CConfigFile {
  public:
    /** Loads the file; throws CBadInputError if it is missing, unreadable or a
     * directory. */
    explicit CIniConfig(const std::string& path);
    /** Never writes back: MRPT's CConfigFile saves modified content to disk in
     * its destructor, which would let --set rewrite the user's file. */
    ~CIniConfig() override;

    const std::string& path() const { return m_path; }
    /** The key's value came from applyOverride() (--set), not the file. */
    bool isOverridden(const std::string& section, const std::string& key) const;
    /** Folder of the config file (absolute), for relative path resolution. */
    const std::string& folder() const { return m_folder; }

    /** Applies a `SECTION.KEY=VALUE` override (the CLI's --set). The section and
     * key must already exist in the file, so that a typo cannot be silently
     * ignored. Throws CBadInputError otherwise. */
    void applyOverride(const std::string& assignment);

    /** Keys present in the file (in the given sections, or all sections if
     * empty) that no code has read so far: "[section] key" strings. */
    std::vector<std::string> unreadKeys(
        const std::vector<std::string>& sections = {}) const;
    /** Throws CBadInputError naming the first unread key, if any. */
    void throwOnUnreadKeys(const std::vector<std::string>& sections = {}) const;
    /** Throws CBadInputError "<file>[ (--set)]: unknown section [s] (known:
     * <known>)", "(--set)" when only --set gave the section. */
    [[noreturn]] void throwUnknownSection(const std::string& section,
                                          const std::string& known) const;

    /** Whether a key exists in the file (does not count as a read). */
    bool hasKey(const std::string& section, const std::string& key) const;
    std::vector<std::string> sections() const;

  protected:
    std::string readString(const std::string& section, const std::string& name,
                           const std::string& defaultStr,
                           bool failIfNotFound = false) const override;
    /** MRPT's write, and hasKey()'s key sets forgotten. */
    void writeString(const std::string& section, const std::string& name,
                     const std::string& str) override;

  private:
    /** Throws CBadInputError (file, line) for a key given twice in a section
     * and for a line that is neither a section, a KEY = VALUE nor a comment:
     * MRPT would keep the last key / drop the line. Checked on the text MRPT
     * reads: after its preprocessor (@define, ${}, $eval{}, line
     * continuation), split at CR, LF and CR+LF as its SimpleIni splits it. */
    static void checkLines(const std::string& path);
    /** Throws CBadInputError naming the new name when the section or key
     * has one (common/renamed_keys.h). */
    void throwIfRenamed(const std::string& section, const std::string& key) const;
    std::string m_path, m_folder;
    mutable std::set<std::pair<std::string, std::string>> m_read;
    /** hasKey(): each section's keys (lower case) by section, listed once: MRPT's
     * getAllKeys() per call made a 10000-waypoint route_file quadratic. */
    mutable std::map<std::string, std::set<std::string>> m_keys;
    std::set<std::pair<std::string, std::string>> m_overridden;  ///< lower case
};

}  // namespace risknav::common
