#pragma once
#include <risknav/common/CValidatedOptions.h>
#include <risknav/common/config_read.h>

#include <cstdint>
#include <string>
#include <vector>

namespace risknav::common {
/** An options struct whose keys are declared once, in declare(): each key's
 * name, member, unit and range and its one-line doc. Loading, saving (with
 * the doc and range as the comment, as MRPT's MRPT_SAVE_CONFIG_VAR_COMMENT
 * writes it), the range checks of validate() and the list of documented keys
 * all come from that declaration, so they cannot disagree. validateRules()
 * keeps only the rules across keys.
 *
 * A derived struct names its section in its constructor (`section = ...`;
 * loadFromConfigFile() sets it to the section read). */
class CDeclaredOptions : public CValidatedOptions {
  public:
    /** What declare() hands each key to. */
    class Visitor {
      public:
        virtual ~Visitor() = default;
        virtual void number(double& v, const char* key, const TRange& range,
                            const char* doc) = 0;
        virtual void integer(int& v, const char* key, const TRange& range,
                             const char* doc) = 0;
        virtual void flag(bool& v, const char* key, const char* doc) = 0;
        /** A list of numbers, each in `each` (its count: a rule). */
        virtual void numbers(std::vector<double>& v, const char* key, const TRange& each,
                             const char* doc) = 0;
        /** One of `allowed`. */
        virtual void choice(std::string& v, const char* key,
                            const std::vector<std::string>& allowed, const char* doc) = 0;
        /** Words separated by spaces, each one of `allowed`, at least one. */
        virtual void words(std::vector<std::string>& v, const char* key,
                           const std::vector<std::string>& allowed, const char* doc) = 0;
        /** A random seed, [0, 2^53] (exact as a double: kMaxSeed). */
        virtual void seed(uint64_t& v, const char* key, const char* doc) = 0;
        /** Free text (a label); `nonEmpty`: "" is refused. */
        virtual void text(std::string& v, const char* key, bool nonEmpty,
                          const char* doc) = 0;
        /** A file path, relative to the config file's folder (readPath());
         * `mustExist`: the file must be there when the key is given ("" =
         * none, unless a rule demands one). */
        virtual void path(std::string& v, const char* key, bool mustExist,
                          const char* doc) = 0;
        /** An angle held in radians (MRPT's convention), written and ranged
         * in degrees in the file (a key named *_deg or MRPT's own). */
        virtual void degrees(double& radians, const char* key, const TRange& rangeDeg,
                             const char* doc) = 0;
    };

    /** One declared key, as the documentation check lists it. */
    struct TKey {
        std::string key, doc, range;  ///< range: e.g. "[1, 1000]" or "true | false"
        std::string defaultText;      ///< the value the struct holds
    };

    std::string section;  ///< the section read (its errors name it)

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                            const std::string& s) final;
    void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                          const std::string& s) const final;
    /** Every declared range, then validateRules(). */
    void validate() const final;
    /** Every declared key with its doc, range and current value. */
    std::vector<TKey> keys() const;

  protected:
    /** Declares every key: v.number(member, "key", range, "doc") etc. */
    virtual void declare(Visitor& v) = 0;
    /** The rules across keys (throws CConfigKeyError). */
    virtual void validateRules() const {}

  private:
    /** declare() for visitors that only read the members. */
    void declareConst(Visitor& v) const;
};
}  // namespace risknav::common
