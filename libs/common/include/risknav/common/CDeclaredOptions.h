#pragma once
#include <risknav/common/CValidatedOptions.h>
#include <risknav/common/config_read.h>

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <cstdint>
#include <optional>
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
/** How many numbers a declared list holds: at least `min`, a multiple of
 * `multiple`, exactly `exact` when > 0; `required`: a missing key is an error
 * at load. An empty list is not saved (it loads back empty). */
struct TListCount {
    size_t min = 0, multiple = 1, exact = 0;
    bool required = false;
};

/** Whitespace-separated paths; "double quotes" keep a path with spaces
 * (an unbalanced quote: CBadInputError naming the file, section and key). */
std::vector<std::string> splitPathList(const mrpt::config::CConfigFileBase& c,
                                       const std::string& s, const std::string& k,
                                       const std::string& v);
/** The inverse of splitPathList(). */
std::string joinPathList(const std::vector<std::string>& paths);

class CDeclaredOptions : public CValidatedOptions {
  public:
    using TCount = TListCount;

    /** What declare() hands each key to. The kinds without a default body
     * are the primitives every visitor implements; the others are built on
     * them. */
    class Visitor {
      public:
        virtual ~Visitor() = default;
        virtual void number(double& v, const char* key, const TRange& range,
                            const char* doc) = 0;
        virtual void integer(int& v, const char* key, const TRange& range,
                             const char* doc) = 0;
        virtual void flag(bool& v, const char* key, const char* doc) = 0;
        /** A list of numbers, each in `each`, `count` of them. */
        virtual void numbers(std::vector<double>& v, const char* key, const TRange& each,
                             const char* doc, const TCount& count = {}) = 0;
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
        /** A number without a default: a missing key is an error at load. */
        virtual void requiredNumber(double& v, const char* key, const TRange& range,
                                    const char* doc) {
            number(v, key, range, doc);
        }
        /** A number that may be absent (then not saved, nothing checked). */
        virtual void optionalNumber(std::optional<double>& v, const char* key,
                                    const TRange& range, const char* doc) = 0;
        /** A required point "x y" (NaN until loaded). */
        void point(mrpt::math::TPoint2D& p, const char* key, const TRange& each,
                   const char* doc);
        /** Points "x0 y0 x1 y1 ..." (count.min / exact in numbers, multiple 2). */
        void points(std::vector<mrpt::math::TPoint2D>& p, const char* key,
                    const TRange& each, const char* doc, TCount count = {});
        /** A required pose "x [m] y [m] heading [deg]", held as MRPT's TPose2D
         * (heading in radians); x and y in `xy`, the heading in `headingDeg`. */
        void pose(mrpt::math::TPose2D& p, const char* key, const TRange& xy,
                  const TRange& headingDeg, const char* doc);
        /** Another declared struct's keys, in this section (its rules too). */
        virtual void include(CDeclaredOptions& sub) { sub.declare(*this); }
        /** sub's keys in this section only when `key` is given: an optional
         * part (a map). `given` says whether the part is in use (saved,
         * checked); a load asks the file whether `key` is there; the key
         * list documents the part always. */
        virtual void includeIfGiven(CDeclaredOptions& sub, const char* key, bool given) {
            if (given)
                include(sub);
        }
        /** File paths, whitespace-separated ("double quotes" keep a path with
         * spaces), each relative to the config file's folder; "" = none.
         * Whether they exist is a rule of the struct's. */
        virtual void paths(std::vector<std::string>& v, const char* key,
                           const char* doc) = 0;
        /** A struct loaded from the section `name` (the value of `key`,
         * declared before): "" = its built-in values, else the section must
         * exist. Saved into that section; validated when `check`. */
        virtual void namedSection(CDeclaredOptions& sub, const std::string& name,
                                  const char* key, bool check = true) = 0;

      protected:
        /** The section a visitor that loads or checks reads ("" for the
         * others: they check nothing). */
        virtual const std::string* checkedSection() const { return nullptr; }
        /** sub's rules across keys (for a visitor that checks). */
        static void rulesOf(const CDeclaredOptions& sub) { sub.validateRules(); }
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
    /** After a load, for defaults that depend on what was read (a name that
     * defaults to the section's). */
    virtual void onLoaded() {}

  private:
    /** declare() for visitors that only read the members. */
    void declareConst(Visitor& v) const;
};
}  // namespace risknav::common
