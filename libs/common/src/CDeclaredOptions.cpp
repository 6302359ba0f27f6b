#include <risknav/common/CBadInputError.h>
#include <risknav/common/CDeclaredOptions.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

namespace risknav::common {
namespace {
using mrpt::config::CConfigFileBase;

std::vector<std::string> splitWords(const std::string& s) {
    std::vector<std::string> w;
    std::istringstream in(s);
    for (std::string x; in >> x;)
        w.push_back(x);
    return w;
}

std::string joined(const std::vector<std::string>& w, const char* sep = " ") {
    std::string s;
    for (const auto& x : w)
        s += (s.empty() ? "" : sep) + x;
    return s;
}

std::string numbersText(const std::vector<double>& v) {
    std::string t;
    for (double x : v)
        t += (t.empty() ? "" : " ") + numberText(x);
    return t;
}

const TRange kSeedRange = TRange::closed(0, kMaxSeed);

double toDegrees(double radians) {
    return radians * 180.0 / M_PI;
}

using TCount = TListCount;

// The count rule as a phrase ("" when any count will do).
std::string countRule(const TCount& n) {
    if (n.exact > 0)
        return "needs exactly " + std::to_string(n.exact) + " numbers";
    std::string t;
    if (n.min > 0)
        t = "needs at least " + std::to_string(n.min) + " numbers";
    if (n.multiple > 1)
        t += (t.empty() ? "needs " : ", ") + std::string("a multiple of ") +
             std::to_string(n.multiple);
    return t;
}

bool countHolds(const TCount& n, size_t size) {
    if (n.exact > 0)
        return size == n.exact;
    return size >= n.min && (n.multiple <= 1 || size % n.multiple == 0);
}

std::string rangeText(const TRange& r) {
    // "must be in [1, 1000]" -> "[1, 1000]" (TRange::describe()'s wording)
    const std::string d = r.describe();
    const std::string lead = "must be in ";
    return d.rfind(lead, 0) == 0 ? d.substr(lead.size()) : d;
}

// "each [a, b] m, needs ..." (the count rule, when there is one)
std::string listRange(const TRange& each, const TCount& n) {
    const std::string rule = countRule(n);
    return "each " + rangeText(each) + (rule.empty() ? "" : "; " + rule) +
           (n.required ? "; required" : "");
}

class CLoader : public CDeclaredOptions::Visitor {
  public:
    CLoader(const CConfigFileBase& c, const std::string& s) : m_c(c), m_s(s) {}
    const std::string* checkedSection() const override { return &m_s; }
    void number(double& v, const char* key, const TRange&, const char*) override {
        v = readDouble(m_c, m_s, key, v);
    }
    void integer(int& v, const char* key, const TRange&, const char*) override {
        v = readInt(m_c, m_s, key, v);
    }
    void flag(bool& v, const char* key, const char*) override {
        v = readBool(m_c, m_s, key, v);
    }
    void numbers(std::vector<double>& v, const char* key, const TRange& each,
                 const char* doc, const TCount& n) override {
        if (n.required && !m_c.keyExists(m_s, key))
            throw CBadInputError(configWhere(m_c, m_s, key) + "[" + m_s + "] " + key +
                                 ": required key is missing (" + doc + ")");
        // the range is checked by validate(), as for single numbers
        v = readNumbers(m_c, m_s, key, v, {}, n.exact > 0 ? 0 : n.min,
                        n.exact > 0 ? 1 : n.multiple);
        if (!countHolds(n, v.size()))
            throwBadKey(m_c, m_s, key, readString(m_c, m_s, key, ""), countRule(n));
    }
    void choice(std::string& v, const char* key, const std::vector<std::string>& allowed,
                const char*) override {
        v = readChoice(m_c, m_s, key, v, allowed);
    }
    void words(std::vector<std::string>& v, const char* key,
               const std::vector<std::string>&, const char*) override {
        v = splitWords(readString(m_c, m_s, key, joined(v)));
    }
    void seed(uint64_t& v, const char* key, const char*) override {
        const double d = readDouble(m_c, m_s, key, double(v), kSeedRange);
        if (d != std::floor(d))  // 1.5 is no seed (it was taken as 1)
            throwBadKey(m_c, m_s, key, readString(m_c, m_s, key, ""), "not an integer");
        v = uint64_t(d);
    }
    void text(std::string& v, const char* key, bool, const char*) override {
        v = readString(m_c, m_s, key, v);
    }
    void path(std::string& v, const char* key, bool mustExist, const char*) override {
        // an empty value is "none": only a given path must exist
        v = readPath(m_c, m_s, key, v,
                     mustExist && !readString(m_c, m_s, key, v).empty());
    }
    void degrees(double& radians, const char* key, const TRange& rangeDeg,
                 const char*) override {
        radians = readDegrees(m_c, m_s, key, radians, rangeDeg);
    }
    void requiredNumber(double& v, const char* key, const TRange& range,
                        const char*) override {
        v = requireDouble(m_c, m_s, key, range);
    }
    void optionalNumber(std::optional<double>& v, const char* key, const TRange&,
                        const char*) override {
        if (m_c.keyExists(m_s, key))
            v = readDouble(m_c, m_s, key, 0.0);
    }
    void include(CDeclaredOptions& sub) override {
        sub.section = m_s;
        Visitor::include(sub);
    }
    void includeIfGiven(CDeclaredOptions& sub, const char* key, bool) override {
        if (m_c.keyExists(m_s, key))
            include(sub);
    }
    void paths(std::vector<std::string>& v, const char* key, const char*) override {
        if (!m_c.keyExists(m_s, key))
            return;
        v.clear();
        for (const auto& p : splitPathList(m_c, m_s, key, readString(m_c, m_s, key, "")))
            v.push_back(configRelativePath(m_c, p));
    }
    void namedSection(CDeclaredOptions& sub, const std::string& name, const char* key,
                      bool) override {
        if (name.empty()) {
            sub.section = m_s + " (built-in " + key + ")";
            return;
        }
        if (!m_c.sectionExists(name))
            throwBadKey(m_c, m_s, key, name, "no section [" + name + "] in the config");
        sub.loadFromConfigFile(m_c, name);
    }

  private:
    const CConfigFileBase& m_c;
    const std::string& m_s;
};

class CSaver : public CDeclaredOptions::Visitor {
  public:
    CSaver(CConfigFileBase& c, const std::string& s) : m_c(c), m_s(s) {}
    void number(double& v, const char* key, const TRange& r, const char* doc) override {
        put(key, numberText(v), doc, rangeText(r));
    }
    void integer(int& v, const char* key, const TRange& r, const char* doc) override {
        put(key, std::to_string(v), doc, rangeText(r));
    }
    void flag(bool& v, const char* key, const char* doc) override {
        put(key, v ? "true" : "false", doc, "true | false");
    }
    void numbers(std::vector<double>& v, const char* key, const TRange& r,
                 const char* doc, const TCount& n) override {
        if (!v.empty())
            put(key, numbersText(v), doc, listRange(r, n));
    }
    void choice(std::string& v, const char* key, const std::vector<std::string>& allowed,
                const char* doc) override {
        put(key, v, doc, joined(allowed, " | "));
    }
    void words(std::vector<std::string>& v, const char* key,
               const std::vector<std::string>& allowed, const char* doc) override {
        put(key, joined(v), doc, "of " + joined(allowed, ", "));
    }
    void seed(uint64_t& v, const char* key, const char* doc) override {
        put(key, std::to_string(v), doc, rangeText(kSeedRange));
    }
    void text(std::string& v, const char* key, bool, const char* doc) override {
        put(key, v, doc, "text");
    }
    void optionalNumber(std::optional<double>& v, const char* key, const TRange& r,
                        const char* doc) override {
        if (v)
            put(key, numberText(*v), doc, rangeText(r));
    }
    void path(std::string& v, const char* key, bool, const char* doc) override {
        put(key, v, doc, "a file path");
    }
    void degrees(double& radians, const char* key, const TRange& rangeDeg,
                 const char* doc) override {
        put(key, numberText(toDegrees(radians)), doc, rangeText(rangeDeg));
    }
    void paths(std::vector<std::string>& v, const char* key, const char* doc) override {
        put(key, joinPathList(v), doc, "file paths");
    }
    void namedSection(CDeclaredOptions& sub, const std::string& name, const char*,
                      bool) override {
        if (!name.empty())
            sub.saveToConfigFile(m_c, name);
    }

  private:
    void put(const char* key, const std::string& value, const char* doc,
             const std::string& range) {
        // "key = value // doc, range", unpadded: MRPT's padding would keep
        // the padded name as the key in a CConfigFileMemory, where a load of
        // what was just saved would then find nothing and keep its defaults.
        // An empty value goes without its comment: MRPT strips a "//"
        // comment only after a value, so "key = // doc" would read as "// doc"
        if (value.empty())
            m_c.write(m_s, key, value);
        else
            m_c.write(m_s, key, value, -1, -1, std::string(doc) + ", " + range);
    }
    CConfigFileBase& m_c;
    const std::string& m_s;
};

class CChecker : public CDeclaredOptions::Visitor {
  public:
    explicit CChecker(const std::string& s) : m_s(s) {}
    const std::string* checkedSection() const override { return &m_s; }
    void number(double& v, const char* key, const TRange& r, const char*) override {
        checkKey(m_s, key, v, r);
    }
    void integer(int& v, const char* key, const TRange& r, const char*) override {
        checkKey(m_s, key, double(v), r);
    }
    void flag(bool&, const char*, const char*) override {}
    void numbers(std::vector<double>& v, const char* key, const TRange& r, const char*,
                 const TCount& n) override {
        checkRule(countHolds(n, v.size()) && (!n.required || !v.empty()), m_s, key,
                  std::to_string(v.size()) + " values",
                  n.required && v.empty() ? "required" : countRule(n));
        checkKey(m_s, key, v, r);
    }
    void choice(std::string& v, const char* key, const std::vector<std::string>& allowed,
                const char*) override {
        checkRule(std::find(allowed.begin(), allowed.end(), v) != allowed.end(), m_s, key,
                  v, "must be one of: " + joined(allowed, ", "));
    }
    void words(std::vector<std::string>& v, const char* key,
               const std::vector<std::string>& allowed, const char*) override {
        checkRule(!v.empty(), m_s, key, "",
                  "needs one or more of: " + joined(allowed, ", "));
        for (const auto& w : v)
            checkRule(std::find(allowed.begin(), allowed.end(), w) != allowed.end(), m_s,
                      key, w, "each must be one of: " + joined(allowed, ", "));
    }
    void seed(uint64_t& v, const char* key, const char*) override {
        checkKey(m_s, key, double(v), kSeedRange);
    }
    void text(std::string& v, const char* key, bool nonEmpty, const char*) override {
        checkRule(!nonEmpty || !v.empty(), m_s, key, v, "must not be empty");
    }
    void path(std::string&, const char*, bool, const char*) override {}
    void degrees(double& radians, const char* key, const TRange& rangeDeg,
                 const char*) override {
        checkKey(m_s, key, toDegrees(radians), rangeDeg);
    }
    void optionalNumber(std::optional<double>& v, const char* key, const TRange& r,
                        const char*) override {
        if (v)
            checkKey(m_s, key, *v, r);
    }
    void include(CDeclaredOptions& sub) override {
        Visitor::include(sub);
        rulesOf(sub);
    }
    void paths(std::vector<std::string>&, const char*, const char*) override {}
    void namedSection(CDeclaredOptions& sub, const std::string&, const char*,
                      bool check) override {
        if (check)
            sub.validate();  // in its own section (or the built-in's name)
    }

  private:
    const std::string& m_s;
};

class CLister : public CDeclaredOptions::Visitor {
  public:
    std::vector<CDeclaredOptions::TKey> keys;
    void number(double& v, const char* key, const TRange& r, const char* doc) override {
        keys.push_back({key, doc, rangeText(r), numberText(v)});
    }
    void integer(int& v, const char* key, const TRange& r, const char* doc) override {
        keys.push_back({key, doc, rangeText(r), std::to_string(v)});
    }
    void flag(bool& v, const char* key, const char* doc) override {
        keys.push_back({key, doc, "true | false", v ? "true" : "false"});
    }
    void numbers(std::vector<double>& v, const char* key, const TRange& r,
                 const char* doc, const TCount& n) override {
        keys.push_back({key, doc, listRange(r, n), numbersText(v)});
    }
    void choice(std::string& v, const char* key, const std::vector<std::string>& allowed,
                const char* doc) override {
        keys.push_back({key, doc, joined(allowed, " | "), v});
    }
    void words(std::vector<std::string>& v, const char* key,
               const std::vector<std::string>& allowed, const char* doc) override {
        keys.push_back({key, doc, "of " + joined(allowed, ", "), joined(v)});
    }
    void seed(uint64_t& v, const char* key, const char* doc) override {
        keys.push_back({key, doc, rangeText(kSeedRange), numberText(double(v))});
    }
    void text(std::string& v, const char* key, bool, const char* doc) override {
        keys.push_back({key, doc, "text", v});
    }
    void path(std::string& v, const char* key, bool, const char* doc) override {
        keys.push_back({key, doc, "a file path", v});
    }
    void includeIfGiven(CDeclaredOptions& sub, const char*, bool) override {
        include(sub);
    }
    void degrees(double& radians, const char* key, const TRange& rangeDeg,
                 const char* doc) override {
        keys.push_back({key, doc, rangeText(rangeDeg), numberText(toDegrees(radians))});
    }
    void optionalNumber(std::optional<double>& v, const char* key, const TRange& r,
                        const char* doc) override {
        keys.push_back({key, doc, rangeText(r), v ? numberText(*v) : ""});
    }
    void paths(std::vector<std::string>& v, const char* key, const char* doc) override {
        keys.push_back({key, doc, "file paths", joinPathList(v)});
    }
    // its keys are in the named section, not in this one
    void namedSection(CDeclaredOptions&, const std::string&, const char*, bool) override {
    }
};
}  // namespace

std::vector<std::string> splitPathList(const CConfigFileBase& c, const std::string& s,
                                       const std::string& k, const std::string& v) {
    std::vector<std::string> out;
    std::string cur;
    bool quoted = false, have = false;
    for (char ch : v) {
        if (ch == '"') {
            quoted = !quoted;
            have = true;
        } else if (std::isspace(static_cast<unsigned char>(ch)) && !quoted) {
            if (have)
                out.push_back(cur);
            cur.clear();
            have = false;
        } else {
            cur += ch;
            have = true;
        }
    }
    if (quoted)
        throwBadKey(c, s, k, v, "unbalanced double quote");
    if (have)
        out.push_back(cur);
    return out;
}

std::string joinPathList(const std::vector<std::string>& paths) {
    std::string t;
    for (const auto& p : paths) {
        const bool space = std::any_of(
            p.begin(), p.end(), [](unsigned char ch) { return std::isspace(ch) != 0; });
        t += (t.empty() ? "" : " ") + (space ? "\"" + p + "\"" : p);
    }
    return t;
}

void CDeclaredOptions::Visitor::point(mrpt::math::TPoint2D& p, const char* key,
                                      const TRange& each, const char* doc) {
    std::vector<double> v;
    if (std::isfinite(p.x) && std::isfinite(p.y))
        v = {p.x, p.y};
    numbers(v, key, each, doc, TCount{0, 1, 2, true});
    if (v.size() == 2)
        p = {v[0], v[1]};
}

void CDeclaredOptions::Visitor::points(std::vector<mrpt::math::TPoint2D>& p,
                                       const char* key, const TRange& each,
                                       const char* doc, TCount count) {
    std::vector<double> v;
    for (const auto& q : p) {
        v.push_back(q.x);
        v.push_back(q.y);
    }
    count.min *= 2;
    count.exact *= 2;
    count.multiple = 2;
    numbers(v, key, each, doc, count);
    p.clear();
    for (size_t i = 0; i + 1 < v.size(); i += 2)
        p.emplace_back(v[i], v[i + 1]);
}

void CDeclaredOptions::Visitor::pose(mrpt::math::TPose2D& p, const char* key,
                                     const TRange& xy, const TRange& headingDeg,
                                     const char* doc) {
    std::vector<double> v;
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.phi))
        v = {p.x, p.y, toDegrees(p.phi)};
    const std::vector<double> before = v;
    // x and y in their range here; the heading's is checked below
    const TRange any{-std::numeric_limits<double>::max(),
                     std::numeric_limits<double>::max(), true, true, ""};
    numbers(v, key, any, doc, TCount{0, 1, 3, true});
    if (v.size() != 3)
        return;
    if (const std::string* section = checkedSection()) {
        const std::string s = numbersText(v);
        checkRule(xy.contains(v[0]) && xy.contains(v[1]), *section, key, s,
                  "x and y " + xy.describe());
        checkRule(headingDeg.contains(v[2]), *section, key, s,
                  "the heading " + headingDeg.describe());
    }
    if (v != before)  // degrees back to radians only for a value read
        p = mrpt::math::TPose2D(v[0], v[1], v[2] * M_PI / 180.0);
}

void CDeclaredOptions::declareConst(Visitor& v) const {
    // the saver, checker and lister only read the members they are handed
    const_cast<CDeclaredOptions*>(this)->declare(v);
}

void CDeclaredOptions::loadFromConfigFile(const CConfigFileBase& c,
                                          const std::string& s) {
    section = s;
    CLoader l(c, s);
    try {
        declare(l);
    } catch (const CConfigKeyError& e) {
        // a rule a load checks (a pose's parts): named with the file and the
        // value as typed, as readers' errors are
        throw CBadInputError(configWhere(c, e.section, e.key) + typedValueMessage(c, e));
    }
    onLoaded();
}

void CDeclaredOptions::saveToConfigFile(CConfigFileBase& c, const std::string& s) const {
    CSaver w(c, s);
    declareConst(w);
}

void CDeclaredOptions::validate() const {
    CChecker k(section);
    declareConst(k);
    validateRules();
}

std::vector<CDeclaredOptions::TKey> CDeclaredOptions::keys() const {
    CLister l;
    declareConst(l);
    return l.keys;
}
}  // namespace risknav::common
