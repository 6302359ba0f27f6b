#include <risknav/common/CDeclaredOptions.h>

#include <algorithm>
#include <cmath>
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

std::string rangeText(const TRange& r) {
    // "must be in [1, 1000]" -> "[1, 1000]" (TRange::describe()'s wording)
    const std::string d = r.describe();
    const std::string lead = "must be in ";
    return d.rfind(lead, 0) == 0 ? d.substr(lead.size()) : d;
}

class CLoader : public CDeclaredOptions::Visitor {
  public:
    CLoader(const CConfigFileBase& c, const std::string& s) : m_c(c), m_s(s) {}
    void number(double& v, const char* key, const TRange&, const char*) override {
        v = readDouble(m_c, m_s, key, v);
    }
    void integer(int& v, const char* key, const TRange&, const char*) override {
        v = readInt(m_c, m_s, key, v);
    }
    void flag(bool& v, const char* key, const char*) override {
        v = readBool(m_c, m_s, key, v);
    }
    void numbers(std::vector<double>& v, const char* key, const TRange&,
                 const char*) override {
        v = readNumbers(m_c, m_s, key, v);
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
        v = uint64_t(readDouble(m_c, m_s, key, double(v), kSeedRange));
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
                 const char* doc) override {
        put(key, numbersText(v), doc, "each " + rangeText(r));
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
        put(key, numberText(double(v)), doc, rangeText(kSeedRange));
    }
    void text(std::string& v, const char* key, bool, const char* doc) override {
        put(key, v, doc, "text");
    }
    void path(std::string& v, const char* key, bool, const char* doc) override {
        put(key, v, doc, "a file path");
    }
    void degrees(double& radians, const char* key, const TRange& rangeDeg,
                 const char* doc) override {
        put(key, numberText(toDegrees(radians)), doc, rangeText(rangeDeg));
    }

  private:
    void put(const char* key, const std::string& value, const char* doc,
             const std::string& range) {
        // "key = value // doc, range", unpadded: MRPT's padding would keep
        // the padded name as the key in a CConfigFileMemory, where a load of
        // what was just saved would then find nothing and keep its defaults
        m_c.write(m_s, key, value, -1, -1, std::string(doc) + ", " + range);
    }
    CConfigFileBase& m_c;
    const std::string& m_s;
};

class CChecker : public CDeclaredOptions::Visitor {
  public:
    explicit CChecker(const std::string& s) : m_s(s) {}
    void number(double& v, const char* key, const TRange& r, const char*) override {
        checkKey(m_s, key, v, r);
    }
    void integer(int& v, const char* key, const TRange& r, const char*) override {
        checkKey(m_s, key, double(v), r);
    }
    void flag(bool&, const char*, const char*) override {}
    void numbers(std::vector<double>& v, const char* key, const TRange& r,
                 const char*) override {
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
                 const char* doc) override {
        keys.push_back({key, doc, "each " + rangeText(r), numbersText(v)});
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
    void degrees(double& radians, const char* key, const TRange& rangeDeg,
                 const char* doc) override {
        keys.push_back({key, doc, rangeText(rangeDeg), numberText(toDegrees(radians))});
    }
};
}  // namespace

void CDeclaredOptions::declareConst(Visitor& v) const {
    // the saver, checker and lister only read the members they are handed
    const_cast<CDeclaredOptions*>(this)->declare(v);
}

void CDeclaredOptions::loadFromConfigFile(const CConfigFileBase& c,
                                          const std::string& s) {
    section = s;
    CLoader l(c, s);
    declare(l);
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
