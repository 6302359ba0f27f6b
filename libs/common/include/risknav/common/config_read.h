#pragma once
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/TPoint2D.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace risknav::common {
/** Allowed interval of a numeric key, with its unit for messages. */
struct TRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minOpen = false;  ///< true: value must be > min (not >=)
    bool maxOpen = false;
    std::string unit;

    static TRange any(const std::string& unit = "") {
        return {-inf(), inf(), false, false, unit};
    }
    static TRange positive(const std::string& unit = "") {
        return {0, inf(), true, false, unit};
    }
    static TRange nonNegative(const std::string& unit = "") {
        return {0, inf(), false, false, unit};
    }
    static TRange closed(double a, double b, const std::string& unit = "") {
        return {a, b, false, false, unit};
    }
    static TRange atLeast(double a, const std::string& unit = "") {
        return {a, inf(), false, false, unit};
    }
    bool contains(double v) const;
    std::string describe() const;  ///< e.g. "must be in (0, inf) m/s"
    static double inf() { return std::numeric_limits<double>::infinity(); }
};

/** The largest seed a config or --seed takes: 2^53, below which every
 * integer is exact as the double the readers parse (so config_effective.ini
 * loads back what was run). */
constexpr double kMaxSeed = 9007199254740992.0;

/** A decimal number as people write it: digits, sign, point, exponent. Not
 * what strtod also takes (hex "0x10", "inf", "nan"), and not a value it
 * rounds to 0 or to a subnormal. The one number rule of every risknav reader
 * (configs, text map formats). */
bool parseNumber(const std::string& txt, double& out);

/** The text without leading and trailing spaces, tabs, CR and LF. */
std::string trim(const std::string& s);
/** The text in lower case (ASCII; MRPT's config keys ignore case). */
std::string lowerCase(std::string s);
/** A class name without its namespace ("mrpt::nav::CHolonomicND":
 * "CHolonomicND"). */
std::string shortClassName(const std::string& name);
/** `m`'s text read back: MRPT's savers pad key names with spaces, and a
 * memory config then does not find them; read back, the keys are trimmed. */
mrpt::config::CConfigFileMemory reparsedConfig(const mrpt::config::CConfigFileMemory& m);
/** Why `path` cannot be read as a file: "" when it is a regular file (or a
 * link to one), else "not found", "is a folder, not a file" or "is not a
 * regular file (a device, FIFO or socket)" (/dev/zero, a FIFO: reading one
 * would not end or would block). A readable file is noted as an input of
 * the run (noteRunInput()): every reader checks its file here first, and no
 * output of the run may then replace it. */
std::string fileProblem(const std::string& path);
/** `s`, or its first `max` bytes and "... (N bytes)" when longer: a message
 * quotes a 10 MB line in a few hundred bytes. */
std::string clippedText(const std::string& s, size_t max = 200);

/** @name Strict typed reads.
 * MRPT's read_double() accepts "0.5 ; comment" as a crash (stod) and "5abc" as 5;
 * these reads accept exactly one number (or the documented list) and throw
 * CBadInputError naming file, section, key, value and the allowed range.
 * A missing key gives the default, except for the require*() variants.
 * @{ */
double readDouble(const mrpt::config::CConfigFileBase& c, const std::string& section,
                  const std::string& key, double def, const TRange& range = {});
double requireDouble(const mrpt::config::CConfigFileBase& c, const std::string& section,
                     const std::string& key, const TRange& range);
/** Reads degrees from the file and returns radians (MRPT convention). */
double readDegrees(const mrpt::config::CConfigFileBase& c, const std::string& section,
                   const std::string& key, double defRad, const TRange& rangeDeg);
int readInt(const mrpt::config::CConfigFileBase& c, const std::string& section,
            const std::string& key, int def, const TRange& range = {});
bool readBool(const mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, bool def);
std::string readString(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::string& key, const std::string& def);
std::string requireString(const mrpt::config::CConfigFileBase& c,
                          const std::string& section, const std::string& key);
/** One of a fixed set of words. */
std::string readChoice(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::string& key, const std::string& def,
                       const std::vector<std::string>& allowed);
/** Whitespace- or comma-separated numbers, optionally in brackets "[1 2 3]".
 * sizeMultiple > 1 demands a count that is a multiple of it (e.g. x y pairs). */
std::vector<double> readNumbers(const mrpt::config::CConfigFileBase& c,
                                const std::string& section, const std::string& key,
                                const std::vector<double>& def, const TRange& range = {},
                                size_t minCount = 0, size_t sizeMultiple = 1);
/** A file path; relative paths resolve against the config file's folder when
 * the config is a CIniConfig. mustExist: throws if the file is not there. */
std::string readPath(const mrpt::config::CConfigFileBase& c, const std::string& section,
                     const std::string& key, const std::string& def, bool mustExist);
/** A path as a config names it: a relative one resolves against the config
 * file's folder when the config is a CIniConfig (what readPath() does, for
 * keys that hold several paths). Lexically normal. */
std::string configRelativePath(const mrpt::config::CConfigFileBase& c,
                               const std::string& path);
/** @} */

/** @name Writing, for saveToConfigFile(): every value reads back to the same bits
 * (so config_effective.ini reproduces a run byte for byte).
 * @{ */
/** Shortest text that reads back to the same double ("0.25", "1e-05", "90"). */
std::string numberText(double v);
void writeKey(mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, double v);
void writeKey(mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, int v);
void writeKey(mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, bool v);
void writeKey(mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, const std::string& v);
void writeKey(mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, const std::vector<double>& v);
/** Radians in code, degrees in the file (MRPT convention). */
void writeDegrees(mrpt::config::CConfigFileBase& c, const std::string& section,
                  const std::string& key, double rad);
/** @} */

/** @name Checks for validate(): throw CConfigKeyError "[section] key = 'value': rule".
 * @{ */
void checkKey(const std::string& section, const std::string& key, double v,
              const TRange& range);
void checkKey(const std::string& section, const std::string& key,
              const std::vector<double>& v, const TRange& range);
/** Radians in code, the range in degrees (as in the file). */
void checkDegrees(const std::string& section, const std::string& key, double rad,
                  const TRange& rangeDeg);
/** Throws CConfigKeyError(section, key, value, rule) unless ok. */
void checkRule(bool ok, const std::string& section, const std::string& key,
               const std::string& value, const std::string& rule);
/** @} */

/** @name Config values that become output file names.
 * @{ */
/** The longest name an output file may have [bytes]: NAME_MAX (255) with
 * room for the 12 bytes a writer's temporary beside it puts before it
 * (exclusiveTempBeside(): ".tmp-XXXXXX-"). */
constexpr size_t kMaxOutputFileName = 235;
/** Throws CConfigKeyError "[section] key = 'value': ..." when `fileName`, the
 * output file name the key's value becomes, is longer than
 * kMaxOutputFileName bytes (the file system would refuse it after the work). */
void checkOutputFileName(const std::string& section, const std::string& key,
                         const std::string& value, const std::string& fileName);
/** Throws CBadInputError naming the key when `outDir`/`fileName` (with the
 * temporaries' prefix) is longer than PATH_MAX - 1 bytes. */
void checkOutputPath(const mrpt::config::CConfigFileBase& c, const std::string& section,
                     const std::string& key, const std::string& value,
                     const std::string& outDir, const std::string& fileName);
/** @} */

/** config_effective.ini: the header naming the source, then the keys the
 * options wrote with saveToConfigFile() into `saved`. */
std::string effectiveConfigText(const std::string& sourcePath,
                                const mrpt::config::CConfigFileMemory& saved);

/** Writes every key of `from` into `to` (same sections), but those for
 * which `skip(section, key)` is true. */
void copyConfigKeys(
    const mrpt::config::CConfigFileBase& from, mrpt::config::CConfigFileBase& to,
    const std::function<bool(const std::string&, const std::string&)>& skip = {});

/** A point for messages: "(x.xx, y.yy)" [m]. */
std::string pointText(double x, double y);

/** A config made of others (a run's config over an MRPT engine file): which
 * one holds a key, so that a message names the file the value is in. */
class CConfigOrigins {
  public:
    virtual ~CConfigOrigins() = default;
    /** The config a read of (section, key) is answered from. */
    virtual const mrpt::config::CConfigFileBase& holderOf(
        const std::string& section, const std::string& key) const = 0;
};

/** "file.ini: " for a CIniConfig, "" otherwise: prefix of every message;
 * with the section and key: "file.ini (--set): " when --set gave that key,
 * of the file that holds the key when `c` is a CConfigOrigins. */
std::string configWhere(const mrpt::config::CConfigFileBase& c);
std::string configWhere(const mrpt::config::CConfigFileBase& c,
                        const std::string& section, const std::string& key);
/** Throws CBadInputError "<file>: [section] key = 'value': <rule>". */
[[noreturn]] void throwBadKey(const mrpt::config::CConfigFileBase& c,
                              const std::string& section, const std::string& key,
                              const std::string& value, const std::string& rule);

class CConfigKeyError;

/** e.what(), but with the value as the config spells it ('1e9', not the
 * '1e+09' validate() prints) when the config's text for that key is that
 * one number. */
std::string typedValueMessage(const mrpt::config::CConfigFileBase& c,
                              const CConfigKeyError& e);

/** Loads an options struct (MRPT style: loadFromConfigFile(c, section) then
 * validate()) and turns a CConfigKeyError from validate() into a
 * CBadInputError that names the file. */
template <class OPTIONS>
void loadOptions(OPTIONS& o, const mrpt::config::CConfigFileBase& c,
                 const std::string& section);

}  // namespace risknav::common

#include <risknav/common/CBadInputError.h>

template <class OPTIONS>
void risknav::common::loadOptions(OPTIONS& o, const mrpt::config::CConfigFileBase& c,
                                  const std::string& section) {
    o.loadFromConfigFile(c, section);
    try {
        o.validate();
    } catch (const CConfigKeyError& e) {
        throw CBadInputError(configWhere(c, e.section, e.key) + typedValueMessage(c, e));
    }
}
