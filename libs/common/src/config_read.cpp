#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/config_read.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;
using mrpt::config::CConfigFileBase;

namespace risknav::common {
std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
        return {};
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}

std::string lowerCase(std::string s) {
    for (auto& ch : s)
        ch = char(std::tolower(static_cast<unsigned char>(ch)));
    return s;
}

std::string shortClassName(const std::string& name) {
    const auto p = name.rfind("::");
    return p == std::string::npos ? name : name.substr(p + 2);
}

mrpt::config::CConfigFileMemory reparsedConfig(const mrpt::config::CConfigFileMemory& m) {
    std::string text;
    m.getContent(text);
    return mrpt::config::CConfigFileMemory(text);
}

namespace {

std::string fmt(double v) {
    if (std::isinf(v))
        return v > 0 ? "inf" : "-inf";
    std::ostringstream o;
    o << v;
    return o.str();
}

// Raw value, or nullopt-like empty flag when missing. MRPT returns the default
// for a missing key; a sentinel tells "missing" from "present but empty".
const char* kMissing = "\x01risknav-missing\x01";

bool present(const CConfigFileBase& c, const std::string& s, const std::string& k,
             std::string& v) {
    v = c.read_string(s, k, kMissing);
    if (v == kMissing)
        return false;
    v = trim(v);
    return true;
}

void checkReadRange(const CConfigFileBase& c, const std::string& s, const std::string& k,
                    const std::string& raw, double v, const TRange& r) {
    if (!r.contains(v))
        throwBadKey(c, s, k, raw, r.describe());
}
}  // namespace

/** A decimal number as people write it: digits, sign, point, exponent. Not
 * what strtod also takes (hex "0x10", "inf", "nan"), and not a value it
 * rounds to 0 or to a subnormal (1e-400 would be read as 0 silently). */
bool parseNumber(const std::string& txt, double& out) {
    if (txt.empty())
        return false;
    for (const char ch : txt)
        if (!std::isdigit(static_cast<unsigned char>(ch)) && ch != '+' && ch != '-' &&
            ch != '.' && ch != 'e' && ch != 'E')
            return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtod(txt.c_str(), &end);
    return end && *end == '\0' && errno != ERANGE && std::isfinite(out);
}

bool TRange::contains(double v) const {
    if (std::isnan(v))
        return false;
    if (minOpen ? !(v > min) : !(v >= min))
        return false;
    if (maxOpen ? !(v < max) : !(v <= max))
        return false;
    return true;
}

std::string TRange::describe() const {
    std::string d = "must be in " + std::string(minOpen ? "(" : "[") + fmt(min) + ", " +
                    fmt(max) + (maxOpen || std::isinf(max) ? ")" : "]");
    if (!unit.empty())
        d += " " + unit;
    return d;
}

void copyConfigKeys(
    const CConfigFileBase& from, CConfigFileBase& to,
    const std::function<bool(const std::string&, const std::string&)>& skip) {
    std::vector<std::string> sections, keys;
    from.getAllSections(sections);
    for (const auto& s : sections) {
        from.getAllKeys(s, keys);
        for (const auto& k : keys)
            if (!skip || !skip(s, k))
                to.write(s, k, from.read_string(s, k, ""));
    }
}

std::string fileProblem(const std::string& path) {
    std::error_code ec;
    const auto st = fs::status(path, ec);
    if (st.type() == fs::file_type::regular) {
        noteRunInput(path);  // no output of this run may replace it
        return "";
    }
    if (ec || st.type() == fs::file_type::not_found)
        return "not found";
    if (st.type() == fs::file_type::directory)
        return "is a folder, not a file";
    return "is not a regular file (a device, FIFO or socket)";
}

std::string clippedText(const std::string& s, size_t max) {
    if (s.size() <= max)
        return s;
    return s.substr(0, max) + "... (" + std::to_string(s.size()) + " bytes)";
}

std::string configWhere(const CConfigFileBase& c) {
    if (const auto* ini = dynamic_cast<const CIniConfig*>(&c))
        return ini->path() + ": ";
    return "";
}

namespace {
const CConfigFileBase& holderOf(const CConfigFileBase& c, const std::string& section,
                                const std::string& key) {
    const CConfigFileBase* h = &c;
    // (bounded: a layered config of layered configs is a few deep)
    for (int depth = 0; depth < 16; depth++) {
        const auto* o = dynamic_cast<const CConfigOrigins*>(h);
        if (!o)
            break;
        h = &o->holderOf(section, key);
    }
    return *h;
}
}  // namespace

std::string configWhere(const CConfigFileBase& cfg, const std::string& section,
                        const std::string& key) {
    const CConfigFileBase& c = holderOf(cfg, section, key);
    if (const auto* ini = dynamic_cast<const CIniConfig*>(&c))
        return ini->path() + (ini->isOverridden(section, key) ? " (--set): " : ": ");
    return "";
}

void throwBadKey(const CConfigFileBase& cfg, const std::string& section,
                 const std::string& key, const std::string& value,
                 const std::string& rule) {
    const CConfigFileBase& c = holderOf(cfg, section, key);
    throw CBadInputError(configWhere(c, section, key) +
                         typedValueMessage(c, CConfigKeyError(clippedText(section, 100),
                                                              clippedText(key, 100),
                                                              clippedText(value), rule)));
}

double readDouble(const CConfigFileBase& c, const std::string& s, const std::string& k,
                  double def, const TRange& r) {
    std::string raw;
    if (!present(c, s, k, raw))
        return def;
    double v = 0;
    if (!parseNumber(raw, v))
        throwBadKey(c, s, k, raw, "not a number");
    checkReadRange(c, s, k, raw, v, r);
    return v;
}

double requireDouble(const CConfigFileBase& c, const std::string& s, const std::string& k,
                     const TRange& r) {
    std::string raw;
    if (!present(c, s, k, raw))
        throw CBadInputError(configWhere(c, s, k) + "[" + s + "] " + k +
                             ": required key is missing (" + r.describe() + ")");
    return readDouble(c, s, k, 0.0, r);
}

double readDegrees(const CConfigFileBase& c, const std::string& s, const std::string& k,
                   double defRad, const TRange& rangeDeg) {
    return readDouble(c, s, k, defRad * 180.0 / M_PI, rangeDeg) * M_PI / 180.0;
}

int readInt(const CConfigFileBase& c, const std::string& s, const std::string& k, int def,
            const TRange& r) {
    std::string raw;
    if (!present(c, s, k, raw))
        return def;
    double v = 0;
    if (!parseNumber(raw, v) || v != std::floor(v) || std::abs(v) > 2e9)
        throwBadKey(c, s, k, raw, "not an integer");
    checkReadRange(c, s, k, raw, v, r);
    return static_cast<int>(v);
}

bool readBool(const CConfigFileBase& c, const std::string& s, const std::string& k,
              bool def) {
    std::string raw;
    if (!present(c, s, k, raw))
        return def;
    const std::string l = lowerCase(raw);
    if (l == "true" || l == "1" || l == "yes" || l == "on")
        return true;
    if (l == "false" || l == "0" || l == "no" || l == "off")
        return false;
    throwBadKey(c, s, k, raw, "must be true or false");
}

std::string readString(const CConfigFileBase& c, const std::string& s,
                       const std::string& k, const std::string& def) {
    std::string raw;
    return present(c, s, k, raw) ? raw : def;
}

std::string requireString(const CConfigFileBase& c, const std::string& s,
                          const std::string& k) {
    std::string raw;
    if (!present(c, s, k, raw) || raw.empty())
        throw CBadInputError(configWhere(c, s, k) + "[" + s + "] " + k +
                             ": required key is missing");
    return raw;
}

std::string readChoice(const CConfigFileBase& c, const std::string& s,
                       const std::string& k, const std::string& def,
                       const std::vector<std::string>& allowed) {
    const std::string v = readString(c, s, k, def);
    if (std::find(allowed.begin(), allowed.end(), v) != allowed.end())
        return v;
    std::string list;
    for (const auto& a : allowed)
        list += (list.empty() ? "" : ", ") + a;
    throwBadKey(c, s, k, v, "must be one of: " + list);
}

std::vector<double> readNumbers(const CConfigFileBase& c, const std::string& s,
                                const std::string& k, const std::vector<double>& def,
                                const TRange& r, size_t minCount, size_t sizeMultiple) {
    std::string raw;
    if (!present(c, s, k, raw))
        return def;
    std::string body = raw;
    if (!body.empty() && body.front() == '[') {
        if (body.back() != ']')
            throwBadKey(c, s, k, raw, "unbalanced '['");
        body = body.substr(1, body.size() - 2);
    }
    std::replace(body.begin(), body.end(), ',', ' ');
    std::istringstream in(body);
    std::vector<double> out;
    std::string tok;
    while (in >> tok) {
        double v = 0;
        if (!parseNumber(tok, v))
            throwBadKey(c, s, k, raw, "'" + tok + "' is not a number");
        checkReadRange(c, s, k, raw, v, r);
        out.push_back(v);
    }
    if (out.size() < minCount)
        throwBadKey(c, s, k, raw,
                    "needs at least " + std::to_string(minCount) + " numbers");
    if (sizeMultiple > 1 && out.size() % sizeMultiple != 0)
        throwBadKey(c, s, k, raw,
                    "needs a multiple of " + std::to_string(sizeMultiple) + " numbers");
    return out;
}

std::string readPath(const CConfigFileBase& c, const std::string& s, const std::string& k,
                     const std::string& def, bool mustExist) {
    std::string v = readString(c, s, k, def);
    if (v.empty()) {
        if (mustExist)
            throw CBadInputError(configWhere(c, s, k) + "[" + s + "] " + k +
                                 ": required key is missing");
        return v;
    }
    const std::string p = configRelativePath(c, v);
    std::error_code ec;
    if (const std::string why = mustExist ? fileProblem(p) : ""; !why.empty())
        throwBadKey(c, s, k, v,
                    (why == "not found" ? "file not found" : why) + " (" + p + ")");
    return p;  // absolute: config_effective.ini lives elsewhere
}

std::string configRelativePath(const CConfigFileBase& c, const std::string& path) {
    fs::path p(path);
    if (p.is_relative())
        if (const auto* ini = dynamic_cast<const CIniConfig*>(&c))
            p = fs::path(ini->folder()) / p;
    // a file a config names is an input of the run, whether or not its
    // reader checks it through fileProblem()
    noteRunInput(p.string());
    return p.lexically_normal().string();
}

std::string typedValueMessage(const mrpt::config::CConfigFileBase& c,
                              const CConfigKeyError& e) {
    if (!c.keyExists(e.section, e.key))
        return e.what();
    // the numbers of the file's text (a list: separated by blanks or commas,
    // in brackets or not) and of the value printed
    auto tokens = [](const std::string& t, const char* seps) {
        std::vector<std::string> out;
        std::string cur;
        for (const char ch : t + seps[0]) {
            if (std::strchr(seps, ch)) {
                if (!cur.empty())
                    out.push_back(cur);
                cur.clear();
            } else {
                cur += ch;
            }
        }
        return out;
    };
    const auto typed = tokens(c.read_string(e.section, e.key, ""), " \t,[]");
    const auto printed = tokens(e.value, " ");
    if (typed.empty() || typed.size() != printed.size())
        return e.what();
    std::string value, rule = e.rule;
    for (size_t k = 0; k < typed.size(); k++) {
        char* end = nullptr;
        const double v = std::strtod(typed[k].c_str(), &end);
        if (*end != '\0' || numberText(v) != printed[k])
            return e.what();  // not another spelling of the same numbers
        value += (k ? " " : "") + typed[k];
        // an element the rule quotes
        const std::string q = "'" + printed[k] + "'";
        if (const auto at = rule.find(q); at != std::string::npos)
            rule.replace(at, q.size(), "'" + typed[k] + "'");
    }
    return "[" + e.section + "] " + e.key + " = '" + value + "': " + rule;
}

std::string pointText(double x, double y) {
    char b[64];
    std::snprintf(b, sizeof(b), "(%.2f, %.2f)", x, y);
    return b;
}

std::string numberText(double v) {
    if (std::isnan(v))
        return "nan";
    if (std::isinf(v))
        return v > 0 ? "inf" : "-inf";
    char b[40];
    for (int digits = 6; digits <= 17; digits++) {
        std::snprintf(b, sizeof(b), "%.*g", digits, v);
        if (std::strtod(b, nullptr) == v)
            break;
    }
    return b;
}

void writeKey(CConfigFileBase& c, const std::string& s, const std::string& k, double v) {
    c.write(s, k, numberText(v));
}
void writeKey(CConfigFileBase& c, const std::string& s, const std::string& k, int v) {
    c.write(s, k, std::to_string(v));
}
void writeKey(CConfigFileBase& c, const std::string& s, const std::string& k, bool v) {
    c.write(s, k, std::string(v ? "true" : "false"));
}
void writeKey(CConfigFileBase& c, const std::string& s, const std::string& k,
              const std::string& v) {
    c.write(s, k, v);
}
void writeKey(CConfigFileBase& c, const std::string& s, const std::string& k,
              const std::vector<double>& v) {
    std::string t;
    for (double x : v)
        t += (t.empty() ? "" : " ") + numberText(x);
    c.write(s, k, t);
}
void writeDegrees(CConfigFileBase& c, const std::string& s, const std::string& k,
                  double rad) {
    writeKey(c, s, k, rad * 180.0 / M_PI);
}

void checkKey(const std::string& s, const std::string& k, double v, const TRange& r) {
    if (!r.contains(v))
        throw CConfigKeyError(s, k, numberText(v), r.describe());
}
void checkKey(const std::string& s, const std::string& k, const std::vector<double>& v,
              const TRange& r) {
    for (double x : v)
        if (!r.contains(x)) {
            std::string t;
            for (double y : v)
                t += (t.empty() ? "" : " ") + numberText(y);
            throw CConfigKeyError(s, k, t, "'" + numberText(x) + "' " + r.describe());
        }
}
void checkDegrees(const std::string& s, const std::string& k, double rad,
                  const TRange& rangeDeg) {
    checkKey(s, k, rad * 180.0 / M_PI, rangeDeg);
}
void checkRule(bool ok, const std::string& s, const std::string& k,
               const std::string& value, const std::string& rule) {
    if (!ok)
        throw CConfigKeyError(s, k, value, rule);
}

void checkOutputFileName(const std::string& section, const std::string& key,
                         const std::string& value, const std::string& fileName) {
    if (fileName.size() <= kMaxOutputFileName)
        return;
    throw CConfigKeyError(section, key, clippedText(value, 60),
                          "makes the output file name '" + clippedText(fileName, 60) +
                              "' " + std::to_string(fileName.size()) +
                              " bytes long; at most " +
                              std::to_string(kMaxOutputFileName) +
                              " (a file name holds 255 bytes, less the prefix of "
                              "the run's temporary file)");
}

void checkOutputPath(const mrpt::config::CConfigFileBase& c, const std::string& section,
                     const std::string& key, const std::string& value,
                     const std::string& outDir, const std::string& fileName) {
    const size_t bytes = fs::absolute(outDir).string().size() + 1 + 20 + fileName.size();
    if (bytes < PATH_MAX)
        return;
    throwBadKey(c, section, key, clippedText(value, 60),
                "makes the output path " + clippedText(outDir, 60) + "/" +
                    clippedText(fileName, 60) + " " + std::to_string(bytes) +
                    " bytes long (with the temporary file's prefix); at most " +
                    std::to_string(PATH_MAX - 1));
}

namespace {
// MRPT's preprocessor expands ${NAME}, $eval{}, $env{} and @define anywhere in
// a file (comments and values alike) and has no escape, so a path or name
// holding one would not load back. Each is written through a variable whose
// value is the bare character: an expanded value is not expanded again.
const std::string kDollarVar = "risknav_dollar", kAtVar = "risknav_at";

std::string escapePreprocessor(const std::string& s, bool& escaped) {
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); i++) {
        const auto at = [&](const char* w) {
            return s.compare(i, std::strlen(w), w) == 0;
        };
        if (at("${") || at("$eval{") || at("$env{")) {
            out += "${" + kDollarVar + "}";
            escaped = true;
        } else if (at("@define")) {
            out += "${" + kAtVar + "}";
            escaped = true;
        } else
            out += s[i];
    }
    return out;
}

// A comment line holds no line break: one in the path would start a line
// MRPT reads as a key.
std::string oneLine(std::string s) {
    for (char& ch : s)
        if (ch == '\n' || ch == '\r')
            ch = '?';
    return s;
}
}  // namespace

std::string effectiveConfigText(const std::string& sourcePath,
                                const mrpt::config::CConfigFileMemory& saved) {
    std::string body;
    saved.getContent(body);
    const std::string text =
        "; Effective configuration of this run: every key with the value used\n"
        "; (from " +
        oneLine(sourcePath) +
        ", --set overrides, or the default), written by the options'\n"
        "; saveToConfigFile(). Running the app on this file reproduces the run.\n\n" +
        body;
    bool escaped = false;
    const std::string out = escapePreprocessor(text, escaped);
    if (!escaped)
        return out;
    return "@define " + kDollarVar + " $\n@define " + kAtVar +
           " @\n; (the two variables above stand for a literal dollar and at sign, "
           "which MRPT's preprocessor would expand)\n" +
           out;
}

}  // namespace risknav::common
