#include <risknav/common/CAppRunner.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/config_read.h>
#include <risknav/common/renamed_keys.h>

#include <mrpt/config/config_parser.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

namespace fs = std::filesystem;
using namespace risknav::common;

namespace {
std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return s;
}

// Runs before the MRPT base class is constructed: MRPT's CConfigFile silently
// accepts a missing file as an empty config, which would turn every key into a
// silent default.
const std::string& checkedConfigPath(const std::string& path) {
    if (path.empty())
        throw CBadInputError("no config file given");
    if (const std::string why = fileProblem(path); !why.empty())
        throw CBadInputError(path + ": config file " + why);
    std::ifstream f(path);
    if (!f.good())
        throw CBadInputError(path + ": config file cannot be read");
    return path;
}
}  // namespace

CIniConfig::CIniConfig(const std::string& path) try : mrpt
    ::config::CConfigFile(checkedConfigPath(path)), m_path(path),
        m_folder(fs::absolute(fs::path(path)).parent_path().string()) {
        discardSavingChanges();
        checkLines(path);
        for (const auto& sec : sections()) {
            std::vector<std::string> keys;
            getAllKeys(sec, keys);
            for (const auto& k : keys)
                throwIfRenamed(sec, k);
        }
    }
catch (const CBadInputError&) {
    throw;
} catch (const std::exception& e) {
    // MRPT's preprocessor throws on a bad @define / $eval; keep one line.
    throw CBadInputError(path + ": cannot parse config file: " + firstLine(e.what()));
}

CIniConfig::~CIniConfig() {
    discardSavingChanges();
}

namespace {
/** The lines of `text` as MRPT's SimpleIni splits them: at CR+LF, a lone CR
 * or a lone LF (a CR-only file is many lines to MRPT, one to getline()). */
std::vector<std::string> mrptLines(const std::string& text) {
    std::vector<std::string> lines(1);
    for (size_t i = 0; i < text.size(); i++) {
        const char ch = text[i];
        if (ch == '\r' || ch == '\n') {
            if (ch == '\r' && i + 1 < text.size() && text[i + 1] == '\n')
                i++;
            lines.emplace_back();
        } else
            lines.back() += ch;
    }
    return lines;
}

/** For each line MRPT's preprocessor keeps, the source line it starts on: its
 * line continuation (a backslash right before a line break) joins lines, and
 * nothing else adds or removes a break. Empty when the count does not match
 * (a backslash ending an @define value or a $env{} holding a break). */
std::vector<size_t> sourceLineNumbers(const std::string& raw, size_t preprocessedLines) {
    std::vector<size_t> starts{1};
    size_t line = 1;
    for (size_t i = 0; i < raw.size(); i++) {
        const char ch = raw[i];
        if (ch != '\r' && ch != '\n')
            continue;
        const bool joined = i > 0 && raw[i - 1] == '\\';
        if (ch == '\r' && i + 1 < raw.size() && raw[i + 1] == '\n')
            i++;
        line++;
        if (!joined)
            starts.push_back(line);
    }
    if (starts.size() != preprocessedLines)
        starts.clear();
    return starts;
}
}  // namespace

void CIniConfig::checkLines(const std::string& path) {
    // MRPT (SimpleIni) keeps the last of two equal keys and drops a line
    // without '=': both would silently change what a run uses. Checked on
    // what MRPT reads: the text after its preprocessor (@define, ${}, $eval{},
    // line continuation), split into lines where SimpleIni splits them, so
    // that neither a CR-only file nor a @define'd name hides a duplicate.
    std::ifstream f(path, std::ios::binary);
    const std::string raw((std::istreambuf_iterator<char>(f)),
                          std::istreambuf_iterator<char>());
    // MRPT's reader takes the text as a C string: it ends at a NUL byte,
    // and every section after it was silently gone
    if (const auto nul = raw.find('\0'); nul != std::string::npos) {
        const size_t n = mrptLines(raw.substr(0, nul)).size();
        throw CBadInputError(path + ": line " + std::to_string(n) +
                             ": a NUL byte (a binary file? MRPT's reader would "
                             "drop everything after it)");
    }
    const std::vector<std::string> lines = mrptLines(mrpt::config::config_parser(raw));
    const std::vector<size_t> source = sourceLineNumbers(raw, lines.size());
    auto lineName = [&](size_t i) {
        return source.empty() ? "line " + std::to_string(i + 1) +
                                    " after MRPT's @define / line-continuation "
                                    "preprocessing"
                              : "line " + std::to_string(source[i]);
    };
    std::string section;
    std::map<std::pair<std::string, std::string>, size_t> seen;
    for (size_t i = 0; i < lines.size(); i++) {
        std::string text = lines[i];
        // a UTF-8 byte order mark (editors on Windows write one), as MRPT's
        // reader skips it
        if (i == 0 && text.rfind("\xEF\xBB\xBF", 0) == 0)
            text.erase(0, 3);
        const std::string line = trim(text);
        if (line.empty() || line[0] == ';' || line[0] == '#' || line.rfind("//", 0) == 0)
            continue;
        const std::string where = path + ": " + lineName(i) + ": ";
        if (line[0] == '[') {
            const auto close = line.find(']');
            if (close == std::string::npos)
                throw CBadInputError(where + "'" + clippedText(line) +
                                     "': a section needs a closing ']'");
            section = trim(line.substr(1, close - 1));
            continue;
        }
        const auto eq = line.find('=');
        // (SimpleIni drops a line with an empty key too)
        if (eq == std::string::npos || eq == 0)
            throw CBadInputError(where + "'" + clippedText(line) + "' in [" +
                                 clippedText(section) + "]: expected KEY = VALUE");
        const std::string key = trim(line.substr(0, eq));
        const auto [it, fresh] =
            seen.emplace(std::make_pair(lower(section), lower(key)), i);
        if (!fresh)
            throw CBadInputError(where + "[" + clippedText(section) + "] " +
                                 clippedText(key) + " is given twice (also " +
                                 lineName(it->second) + ")");
    }
}

std::string CIniConfig::readString(const std::string& section, const std::string& name,
                                   const std::string& defaultStr,
                                   bool failIfNotFound) const {
    m_read.emplace(lower(section), lower(name));
    return mrpt::config::CConfigFile::readString(section, name, defaultStr,
                                                 failIfNotFound);
}

void CIniConfig::applyOverride(const std::string& assignment) {
    const auto eq = assignment.find('=');
    const std::string lhs = assignment.substr(0, eq);
    const auto dot = lhs.rfind('.');
    if (eq == std::string::npos || dot == std::string::npos || dot == 0 ||
        dot + 1 == lhs.size())
        throw CBadInputError("--set '" + clippedText(assignment) +
                             "': expected SECTION.KEY=VALUE");
    // (a line break would end the one-line message, and the config's own
    // lines cannot hold one either)
    if (const auto brk = assignment.find_first_of(std::string("\n\r\0", 3));
        brk != std::string::npos)
        throw CBadInputError("--set '" + clippedText(assignment.substr(0, brk)) +
                             "...': a line break or NUL byte in the value");
    // Written into the in-memory config; a key that no code reads is then
    // reported by throwOnUnreadKeys(), so a typo in --set is not ignored.
    write(lhs.substr(0, dot), lhs.substr(dot + 1), assignment.substr(eq + 1));
    discardSavingChanges();  // write() marks the file modified again
    m_overridden.emplace(lower(lhs.substr(0, dot)), lower(lhs.substr(dot + 1)));
    throwIfRenamed(lhs.substr(0, dot), lhs.substr(dot + 1));
}

void CIniConfig::throwIfRenamed(const std::string& section,
                                const std::string& key) const {
    const std::string where =
        m_path + (isOverridden(section, key) ? " (--set)" : "") + ": ";
    if (const auto now = renamedSection(section))
        throw CBadInputError(where + "section [" + clippedText(section) + "] is now [" +
                             *now + "]");
    if (const auto now = renamedKey(section, key))
        throw CBadInputError(where + "[" + clippedText(section) + "] " +
                             clippedText(key) + " is now " + *now);
}

bool CIniConfig::isOverridden(const std::string& section, const std::string& key) const {
    return m_overridden.count({lower(section), lower(key)}) > 0;
}

bool CIniConfig::hasKey(const std::string& section, const std::string& key) const {
    auto it = m_keys.find(section);
    if (it == m_keys.end()) {
        std::vector<std::string> keys;
        getAllKeys(section, keys);
        std::set<std::string> low;
        for (const auto& k : keys)
            low.insert(lower(k));
        it = m_keys.emplace(section, std::move(low)).first;
    }
    return it->second.count(lower(key)) > 0;
}

void CIniConfig::writeString(const std::string& section, const std::string& name,
                             const std::string& str) {
    mrpt::config::CConfigFile::writeString(section, name, str);
    m_keys.clear();
}

std::vector<std::string> CIniConfig::sections() const {
    std::vector<std::string> s;
    getAllSections(s);
    return s;
}

std::vector<std::string> CIniConfig::unreadKeys(
    const std::vector<std::string>& only) const {
    std::vector<std::string> out;
    for (const auto& sec : only.empty() ? sections() : only) {
        std::vector<std::string> keys;
        getAllKeys(sec, keys);
        for (const auto& k : keys)
            if (!m_read.count({lower(sec), lower(k)}))
                out.push_back("[" + sec + "] " + k);
    }
    return out;
}

void CIniConfig::throwUnknownSection(const std::string& section,
                                     const std::string& known) const {
    std::vector<std::string> keys;
    getAllKeys(section, keys);
    const bool fromSet =
        !keys.empty() && std::all_of(keys.begin(), keys.end(), [&](const std::string& k) {
            return isOverridden(section, k);
        });
    throw CBadInputError(m_path + (fromSet ? " (--set)" : "") + ": unknown section [" +
                         clippedText(section) + "] (known: " + known + ")");
}

void CIniConfig::throwOnUnreadKeys(const std::vector<std::string>& only) const {
    const auto unknown = unreadKeys(only);
    if (unknown.empty())
        return;
    // "[section] key": a key that came from --set is said to
    const std::string& first = unknown.front();
    const auto close = first.find("] ");
    const bool fromSet =
        close != std::string::npos &&
        isOverridden(first.substr(1, close - 1), first.substr(close + 2));
    std::string msg =
        m_path + (fromSet ? " (--set)" : "") + ": unknown key " + clippedText(first);
    if (unknown.size() > 1)
        msg += " (and " + std::to_string(unknown.size() - 1) + " more)";
    throw CBadInputError(msg + "; see config/ for the documented keys");
}
