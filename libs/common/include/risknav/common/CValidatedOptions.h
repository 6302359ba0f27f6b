#pragma once
#include <mrpt/config/CLoadableOptions.h>

namespace risknav::common {
/** Base of every risknav options struct: MRPT's CLoadableOptions (so that
 * loadFromConfigFile / saveToConfigFile work as for MRPT's own options, and
 * config_effective.ini is written by the options themselves) plus validate().
 *
 * loadFromConfigFile() only parses (a value that is not a number, a word that
 * is not one of the choices); every range and consistency rule lives in
 * validate(), so options filled in from code are checked by the same rules as
 * options read from a file. */
class CValidatedOptions : public mrpt::config::CLoadableOptions {
  public:
    /** Throws CConfigKeyError (section, key, value, rule) for the first value
     * out of its range or inconsistent with another. */
    virtual void validate() const = 0;
};

}  // namespace risknav::common
