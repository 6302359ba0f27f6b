#pragma once
#include <stdexcept>
#include <string>

namespace risknav::common {
/** Thrown for anything the user got wrong: usage, config file, config key,
 * input file. Apps turn it into a one-line message on stderr and exit code 2.
 * The message is complete (file, section, key, value, allowed range) so that
 * no caller needs to add context. */
class CBadInputError : public std::runtime_error {
  public:
    explicit CBadInputError(const std::string& msg) : std::runtime_error(msg) {}
};

/** A bad value found by an options struct's validate(), which knows section,
 * key and the rule but not the file; loadOptions() adds the file name. */
class CConfigKeyError : public std::runtime_error {
  public:
    CConfigKeyError(const std::string& section, const std::string& key,
                    const std::string& value, const std::string& rule)
        : std::runtime_error("[" + section + "] " + key + " = '" + value + "': " + rule),
          section(section),
          key(key),
          value(value),
          rule(rule) {}
    std::string section, key, value, rule;
};

}  // namespace risknav::common
