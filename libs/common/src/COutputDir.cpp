#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/config_read.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace risknav::common {
namespace {
constexpr const char* kStagePrefix = ".risknav-stage-";
// The owner marker's whole content: a folder of the prefix's name without it
// is somebody else's and never removed.
constexpr const char* kOwnerText = "risknav staging folder 1\n";
constexpr const char* kJournalHead = "risknav commit journal 1\n";
constexpr const char* kManifestHead = "risknav output manifest ";
constexpr size_t kMaxMetaBytes = 1 << 20;  // a manifest or journal is a few KB

std::function<void(int)>& stepHook() {
    static std::function<void(int)> hook;
    return hook;
}

enum class TKind { None, File, Dir, Other };

// What is at `p` itself (a symlink is Other, never followed).
TKind kindOf(const std::string& p) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0)
        return TKind::None;
    if (S_ISREG(st.st_mode))
        return TKind::File;
    if (S_ISDIR(st.st_mode))
        return TKind::Dir;
    return TKind::Other;
}

const char* kindName(TKind k) {
    switch (k) {
        case TKind::File:
            return "a file";
        case TKind::Dir:
            return "a folder";
        default:
            return "a symbolic link or special file";
    }
}

std::string join(const std::string& a, const std::string& b) {
    return a + "/" + b;
}

// A name the run writes in the folder itself: one plain, visible component.
bool plainName(const std::string& n) {
    return !n.empty() && n.size() <= NAME_MAX && n[0] != '.' &&
           n.find('/') == std::string::npos && n.find('\0') == std::string::npos;
}

void writeNewFile(const std::string& path, const std::string& content, bool sync,
                  int how = O_EXCL) {
    const int fd =
        ::open(path.c_str(), O_WRONLY | O_CREAT | how | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        throw writeFailure(path, errno);
    size_t done = 0;
    while (done < content.size()) {
        const ssize_t w = ::write(fd, content.data() + done, content.size() - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            const int e = w < 0 ? errno : ENOSPC;
            ::close(fd);
            throw writeFailure(path, e);
        }
        done += size_t(w);
    }
    if ((sync && ::fsync(fd) != 0) || ::close(fd) != 0)
        throw writeFailure(path, errno);
}

// A small regular file read without following a symlink at its name and
// without blocking (a FIFO planted there); "" if absent or anything else.
std::string readSmall(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return "";
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        return "";
    }
    std::string s;
    char buf[4096];
    for (;;) {
        const ssize_t r = ::read(fd, buf, sizeof(buf));
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0 || s.size() + size_t(r) > kMaxMetaBytes)
            break;
        s.append(buf, size_t(r));
    }
    ::close(fd);
    return s;
}

void syncDir(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
}

void step(int& n) {
    if (stepHook())
        stepHook()(++n);
}

struct TEntry {
    TKind kind;
    std::string name;
};

/** The last run's files and folders, and the files in those folders. Only
 * plain names count (a run writes no others: a name that is absolute, "..",
 * hidden or deeper than one folder is ignored, for the manifest is data),
 * and only in a file that starts as a manifest does. Version 1 listed files
 * only. */
struct TManifest {
    bool valid = false;
    std::string app;
    std::vector<TEntry> entries;
    std::map<std::string, std::set<std::string>> inner;  // folder -> its files

    static bool isManifest(const std::string& text) {
        return text.rfind(kManifestHead, 0) == 0;
    }
    static TManifest read(const std::string& dir) {
        TManifest m;
        const std::string text = readSmall(join(dir, COutputDir::kManifest));
        m.valid = isManifest(text);
        if (!m.valid)
            return m;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            if (line.rfind("app ", 0) == 0)
                m.app = line.substr(4);
            const bool file = line.rfind("file ", 0) == 0,
                       folder = line.rfind("dir ", 0) == 0;
            if (!file && !folder)
                continue;
            const std::string name = line.substr(file ? 5 : 4);
            const auto slash = name.find('/');
            if (file && slash != std::string::npos) {
                const std::string top = name.substr(0, slash),
                                  rest = name.substr(slash + 1);
                if (plainName(top) && plainName(rest))
                    m.inner[top].insert(rest);
            } else if (plainName(name)) {
                m.entries.push_back({file ? TKind::File : TKind::Dir, name});
            }
        }
        return m;
    }
    bool lists(const std::string& name, TKind kind) const {
        return std::any_of(entries.begin(), entries.end(), [&](const TEntry& e) {
            return e.name == name && e.kind == kind;
        });
    }
    std::string text() const {
        std::string t = std::string(kManifestHead) + "2\napp " + app + "\n";
        for (const auto& e : entries) {
            t += (e.kind == TKind::Dir ? "dir " : "file ") + e.name + "\n";
            if (const auto it = inner.find(e.name);
                e.kind == TKind::Dir && it != inner.end())
                for (const auto& f : it->second)
                    t += "file " + e.name + "/" + f + "\n";
        }
        return t;
    }
};

struct TJournalOp {
    bool place;  // place S/new/name at dir/name, else drop dir/name
    std::string name;
};

std::string journalText(const std::vector<TJournalOp>& ops) {
    std::string t = kJournalHead;
    for (const auto& op : ops)
        t += (op.place ? "place " : "drop ") + op.name + "\n";
    return t + "end\n";
}

// A journal as written by journalText(), or nothing (torn or foreign).
std::optional<std::vector<TJournalOp>> parseJournal(const std::string& text) {
    if (text.rfind(kJournalHead, 0) != 0)
        return std::nullopt;
    std::istringstream in(text.substr(std::strlen(kJournalHead)));
    std::vector<TJournalOp> ops;
    std::string line;
    while (std::getline(in, line)) {
        if (line == "end")
            return ops;
        const bool place = line.rfind("place ", 0) == 0,
                   drop = line.rfind("drop ", 0) == 0;
        const std::string name = line.substr(place ? 6 : 5);
        if ((!place && !drop) || (!plainName(name) && name != COutputDir::kManifest))
            return std::nullopt;
        ops.push_back({place, name});
    }
    return std::nullopt;
}

/** Carries out a journal's renames; each op is skipped when already done, so
 * that a killed commit is completed by running it again. `undo` receives
 * (from, to) for each rename done, to be reversed if a later one fails. */
void applyJournal(const std::string& dir, const std::string& stage,
                  const std::vector<TJournalOp>& ops, int& steps,
                  std::vector<std::pair<std::string, std::string>>& undo) {
    // (a failure names the result, never the staging folder's paths)
    auto move = [&](const std::string& from, const std::string& to,
                    const std::string& at) {
        step(steps);
        if (::rename(from.c_str(), to.c_str()) != 0)
            throw std::runtime_error("cannot replace " + clippedText(at, 200) + ": " +
                                     std::strerror(errno));
        undo.emplace_back(from, to);
    };
    for (const auto& op : ops) {
        const std::string at = join(dir, op.name), staged = join(stage + "/new", op.name),
                          aside = join(stage + "/old", op.name);
        if (op.place) {
            if (kindOf(staged) == TKind::None)
                continue;  // placed before the kill
            if (kindOf(at) != TKind::None && kindOf(aside) == TKind::None)
                move(at, aside, at);
            move(staged, at, at);
        } else if (kindOf(at) != TKind::None && kindOf(aside) == TKind::None) {
            move(at, aside, at);
        }
    }
}

/** Removes a staging folder, its owner marker last: a kill or a file that
 * cannot be removed leaves a folder the next run still recognizes. */
void removeStage(const std::string& stage) {
    std::error_code ec;
    bool all = true;
    for (const auto& e : fs::directory_iterator(stage, ec))
        if (e.path().filename() != "owner") {
            fs::remove_all(e.path(), ec);  // never follows a symlink inside
            all = all && !ec;
        }
    if (all && !ec) {
        fs::remove(join(stage, "owner"), ec);
        fs::remove(stage, ec);
    }
}

// A staging folder left by a run (killed, or that failed to remove it):
// completed if its journal says the commit was decided, then removed.
void recoverStage(const std::string& dir, const std::string& stage) {
    if (kindOf(stage) != TKind::Dir || kindOf(join(stage, "owner")) != TKind::File ||
        readSmall(join(stage, "owner")) != kOwnerText)
        return;  // not a risknav run's: left alone
    if (kindOf(join(stage, "journal")) == TKind::File)
        if (const auto ops = parseJournal(readSmall(join(stage, "journal")))) {
            int steps = 0;
            std::vector<std::pair<std::string, std::string>> undo;
            applyJournal(dir, stage, *ops, steps, undo);
            syncDir(dir);
        }
    removeStage(stage);
}

struct TInput {
    dev_t dev;
    ino_t ino;
    std::string path;  // absolute, lexically normal
};
std::mutex& inputsMutex() {
    static std::mutex m;
    return m;
}
std::vector<TInput>& inputs() {
    static std::vector<TInput> v;
    return v;
}
}  // namespace

void noteRunInput(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        return;
    std::error_code ec;
    const fs::path abs = fs::weakly_canonical(fs::absolute(path, ec), ec);
    std::lock_guard<std::mutex> lock(inputsMutex());
    for (const auto& i : inputs())
        if (i.dev == st.st_dev && i.ino == st.st_ino)
            return;
    inputs().push_back({st.st_dev, st.st_ino, abs.lexically_normal().string()});
}

bool isRunInput(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        return false;
    std::lock_guard<std::mutex> lock(inputsMutex());
    for (const auto& i : inputs())
        if (i.dev == st.st_dev && i.ino == st.st_ino)
            return true;
    return false;
}

std::string shownOutputPath(const std::string& path) {
    const auto s = path.rfind(std::string("/") + kStagePrefix);
    if (s == std::string::npos)
        return path;
    // <dir>/.risknav-stage-X/new/<name> and <dir>/.risknav-stage-X/scratch/<sub>/<name>
    const auto inner = path.find('/', s + 1);
    if (inner == std::string::npos)
        return path;
    size_t rest = std::string::npos;
    if (path.compare(inner, 5, "/new/") == 0)
        rest = inner + 5;
    else if (path.compare(inner, 9, "/scratch/") == 0 &&
             path.find('/', inner + 9) != std::string::npos)
        rest = path.find('/', inner + 9) + 1;
    return rest == std::string::npos ? path : path.substr(0, s + 1) + path.substr(rest);
}

std::runtime_error writeFailure(const std::string& path, int errnum) {
    return std::runtime_error("cannot write " + clippedText(shownOutputPath(path), 200) +
                              ": " + std::strerror(errnum ? errnum : EIO));
}

std::string exclusiveTempBeside(const std::string& path) {
    const fs::path p(path);
    const std::string suffix = "-" + p.filename().string();
    std::string tmpl = (p.parent_path() / (".tmp-XXXXXX" + suffix)).string();
    const int fd = ::mkostemps(tmpl.data(), int(suffix.size()), O_CLOEXEC);
    if (fd < 0)
        throw writeFailure(path, errno);
    ::close(fd);
    return tmpl;
}

void writeFileAtomic(const std::string& path, const std::string& content) {
    const std::string tmp = exclusiveTempBeside(path);
    try {
        writeBytes(tmp, content);
    } catch (...) {
        ::unlink(tmp.c_str());
        throw;
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const int e = errno;
        ::unlink(tmp.c_str());
        throw writeFailure(path, e);
    }
}

void writeBytes(const std::string& path, const std::string& content) {
    writeNewFile(path, content, false, O_TRUNC);
}

void COutputDir::setCommitStepHook(std::function<void(int)> hook) {
    stepHook() = std::move(hook);
}

namespace {
// "out/", "out/." and "out/./" name the folder "out": a trailing slash would
// make lstat() follow a symlink at that name.
std::string folderName(const std::string& dir) {
    std::string d = fs::path(dir).lexically_normal().string();
    while (d.size() > 1 && d.back() == '/')
        d.pop_back();
    return d.empty() ? "." : d;
}
}  // namespace

COutputDir::COutputDir(const std::string& given, const std::string& app,
                       const std::vector<std::string>& outputs)
    : m_dir(folderName(given)), m_app(app) {
    const std::string& dir = m_dir;
    const std::string shown = clippedText(dir, 200);
    // Names the file system cannot hold fail here, not after the work.
    for (const auto& part : fs::path(dir))
        if (part.string().size() > NAME_MAX)
            throw CBadInputError(shown + ": a folder name of " +
                                 std::to_string(part.string().size()) +
                                 " bytes (the file system takes at most " +
                                 std::to_string(NAME_MAX) + ")");
    if (fs::absolute(dir).string().size() > PATH_MAX - 2 * NAME_MAX)
        throw CBadInputError(shown + ": the output folder's path is too long (" +
                             std::to_string(fs::absolute(dir).string().size()) +
                             " bytes; at most " +
                             std::to_string(PATH_MAX - 2 * NAME_MAX) + ")");
    if (kindOf(dir) == TKind::Other)
        throw CBadInputError(shown +
                             ": the output folder is a symbolic link or special file; "
                             "give the folder itself");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (kindOf(dir) != TKind::Dir)
        throw CBadInputError(shown + ": cannot create the output folder" +
                             (ec ? " (" + ec.message() + ")" : std::string()));
    // One run per folder at a time: a lock on the folder itself (no file to
    // leave behind; the lock dies with the process).
    m_lockFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (m_lockFd < 0)
        throw CBadInputError(shown + ": cannot open the output folder (" +
                             std::strerror(errno) + ")");
    if (::flock(m_lockFd, LOCK_EX | LOCK_NB) != 0) {
        ::close(m_lockFd);
        m_lockFd = -1;
        throw CBadInputError(shown +
                             ": the output folder is in use by another risknav run");
    }
    try {
        for (const auto& e : fs::directory_iterator(dir, ec))
            if (e.path().filename().string().rfind(kStagePrefix, 0) == 0)
                recoverStage(dir, e.path().string());
        // a folder the user may not write in is bad input; a full disk is not
        auto cannot = [&](const std::string& what, int err) {
            if (err == EACCES || err == EPERM || err == EROFS)
                throw CBadInputError(shown + ": output folder is not writable (" +
                                     std::strerror(err) + ")");
            throw writeFailure(what, err);
        };
        std::string tmpl = join(dir, std::string(kStagePrefix) + "XXXXXX");
        if (!::mkdtemp(tmpl.data()))
            cannot(dir, errno);
        m_stage = tmpl;
        try {
            writeNewFile(join(m_stage, "owner"), kOwnerText, false);
        } catch (const std::runtime_error&) {
            cannot(dir, errno);
        }
        for (const char* sub : {"new", "old", "scratch"})
            if (::mkdir(join(m_stage, sub).c_str(), 0700) != 0)
                cannot(dir, errno);
        // Before the work: the names this run writes, and everything the
        // last run's manifest lists (its commit replaces or removes each).
        checkReplaceable(kManifest);
        checkReplaceable("summary.json");
        checkReplaceable("config_effective.ini");
        for (const auto& o : outputs)
            checkReplaceable(o.substr(0, o.find('/')));
        // (an entry now of another kind than listed is no longer the run's:
        // left alone)
        for (const auto& e : TManifest::read(dir).entries)
            if (kindOf(finalPath(e.name)) == e.kind)
                checkReplaceable(e.name);
    } catch (const std::runtime_error&) {
        // (the destructor does not run for a throwing constructor)
        if (!m_stage.empty())
            removeStage(m_stage);
        ::close(m_lockFd);
        throw;
    }
}

COutputDir::~COutputDir() {
    if (!m_stage.empty() && kindOf(m_stage) == TKind::Dir)
        removeStage(m_stage);  // (after a commit: what is left if its last step failed)
    if (m_lockFd >= 0)
        ::close(m_lockFd);
}

void COutputDir::checkReplaceable(const std::string& top) const {
    const std::string at = finalPath(top);
    const TKind k = kindOf(at);
    if (k == TKind::None)
        return;
    const std::string shown = clippedText(at, 200);
    const std::string advice = "; move it or give another --out";
    if (top == kManifest) {
        if (k == TKind::File && TManifest::isManifest(readSmall(at)))
            return;
        throw CBadInputError(shown + ": " + kindName(k) +
                             " that is not a risknav manifest is in the way of the "
                             "run's manifest" +
                             advice);
    }
    if (k == TKind::Other)
        throw CBadInputError(shown +
                             ": a symbolic link or special file (risknav writes "
                             "none) is in the way of an output" +
                             advice);
    if (isRunInput(at))
        throw CBadInputError(shown +
                             ": is an input of this run, which its results would replace "
                             "or remove (give another --out)");
    const TManifest last = TManifest::read(m_dir);
    if (!last.lists(top, k))
        throw CBadInputError(shown + ": " + kindName(k) +
                             " that no risknav run wrote is in the way of an output (not "
                             "listed in " +
                             kManifest + ")" + advice);
    if (k == TKind::File)
        return;
    // A folder of the last run's is replaced or removed whole: only if it
    // holds nothing but the files that run wrote there, none of them read by
    // this run (also through a symlink elsewhere).
    std::lock_guard<std::mutex> lock(inputsMutex());
    const std::string abs =
        fs::weakly_canonical(fs::absolute(at)).lexically_normal().string() + "/";
    for (const auto& i : inputs())
        if (i.path.rfind(abs, 0) == 0)
            throw CBadInputError(shown + ": holds " + clippedText(i.path, 200) +
                                 ", an input of this run, which its results would "
                                 "replace or remove (give another --out)");
    const auto listed = last.inner.find(top);
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(at, ec)) {
        const std::string name = e.path().filename().string();
        if (kindOf(e.path().string()) != TKind::File || listed == last.inner.end() ||
            !listed->second.count(name))
            throw CBadInputError(clippedText(e.path().string(), 200) +
                                 ": not written by a risknav run (not listed in " +
                                 kManifest + "), in the folder " + top +
                                 " that this run replaces" + advice);
    }
    if (ec)
        throw CBadInputError(shown + ": cannot list the folder (" + ec.message() + ")");
}

std::string COutputDir::finalPath(const std::string& name) const {
    return join(m_dir, name);
}

std::string COutputDir::stage(const std::string& name) {
    for (const auto& s : m_staged)
        if (s.second == name)
            return s.first;
    std::vector<std::string> parts;
    for (const auto& p : fs::path(name))
        parts.push_back(p.string());
    const bool ok = !parts.empty() && !fs::path(name).is_absolute() &&
                    std::all_of(parts.begin(), parts.end(), plainName);
    if (!ok)
        throw std::logic_error("COutputDir::stage: '" + name +
                               "' is not a relative path of plain names");
    bool known = false;
    for (const auto& s : m_staged)
        known = known || s.second.substr(0, s.second.find('/')) == parts.front();
    if (!known)
        checkReplaceable(parts.front());
    std::string path = m_stage + "/new";
    for (size_t i = 0; i + 1 < parts.size(); i++) {
        path = join(path, parts[i]);
        if (::mkdir(path.c_str(), 0755) != 0 && errno != EEXIST)
            throw writeFailure(path, errno);
    }
    path = join(path, parts.back());
    writeNewFile(path, "", false);
    m_staged.emplace_back(path, name);
    return path;
}

std::string COutputDir::scratchDir(const std::string& name) {
    if (!plainName(name))
        throw std::logic_error("COutputDir::scratchDir: '" + name +
                               "' is not a plain name");
    const std::string p = join(m_stage + "/scratch", name);
    if (::mkdir(p.c_str(), 0700) != 0 && errno != EEXIST)
        throw writeFailure(p, errno);
    return p;
}

void COutputDir::writeText(const std::string& name, const std::string& content) {
    writeBytes(stage(name), content);
}

void COutputDir::commitInto(const std::string& sub) {
    if (!plainName(sub))
        throw std::logic_error("COutputDir::commitInto: '" + sub +
                               "' is not a plain name");
    m_sub = sub;
}

void COutputDir::commit() {
    const std::string fresh = m_stage + "/new";
    // A result that vanished (a writer that renamed it away, a bug) would
    // leave the earlier file of its name beside the new set.
    for (const auto& [path, name] : m_staged)
        if (kindOf(path) != TKind::File)
            throw std::runtime_error("the result " + finalPath(name) +
                                     " was not written");
    const TManifest last = TManifest::read(m_dir);
    TManifest next;
    std::vector<std::string> tops;
    if (!m_sub.empty()) {
        // The staged set becomes the subfolder: the last run's set stays, with
        // the subfolder added to it.
        const std::string moved = m_stage + "/into";
        if (::rename(fresh.c_str(), moved.c_str()) != 0 ||
            ::mkdir(fresh.c_str(), 0700) != 0 ||
            ::rename(moved.c_str(), join(fresh, m_sub).c_str()) != 0)
            throw writeFailure(finalPath(m_sub), errno);
        tops.push_back(m_sub);
        next.app = last.app.empty() ? m_app : last.app;
        for (const auto& e : last.entries)
            if (e.name != m_sub)
                next.entries.push_back(e);
        next.entries.push_back({TKind::Dir, m_sub});
        next.inner = last.inner;
        next.inner.erase(m_sub);
        for (const auto& [path, name] : m_staged)
            next.inner[m_sub].insert(fs::path(name).filename().string());
    } else {
        next.app = m_app;
        for (const auto& s : m_staged) {
            const std::string top = s.second.substr(0, s.second.find('/'));
            if (std::find(tops.begin(), tops.end(), top) == tops.end()) {
                tops.push_back(top);
                next.entries.push_back({kindOf(join(fresh, top)), top});
            }
            if (top != s.second)
                next.inner[top].insert(s.second.substr(top.size() + 1));
        }
    }
    checkReplaceable(kManifest);
    for (const auto& top : tops)
        checkReplaceable(top);
    writeNewFile(join(fresh, kManifest), next.text(), false);
    std::vector<TJournalOp> ops;
    for (const auto& top : tops)
        ops.push_back({true, top});
    if (m_sub.empty())
        for (const auto& e : last.entries)
            if (std::find(tops.begin(), tops.end(), e.name) == tops.end() &&
                kindOf(finalPath(e.name)) == e.kind) {
                checkReplaceable(e.name);
                ops.push_back({false, e.name});
            }
    ops.push_back({true, kManifest});  // last: until it is in place, the last
                                       // manifest still names what is replaced
    // The point of no return: once the journal is in place (written whole and
    // synced first), a kill leaves a commit the next run completes.
    int steps = 0;
    const std::string journal = join(m_stage, "journal");
    step(steps);
    writeNewFile(journal + ".part", journalText(ops), true);
    step(steps);
    if (::rename((journal + ".part").c_str(), journal.c_str()) != 0)
        throw writeFailure(finalPath(kManifest), errno);
    syncDir(m_stage);
    std::vector<std::pair<std::string, std::string>> undo;
    try {
        applyJournal(m_dir, m_stage, ops, steps, undo);
    } catch (...) {
        for (auto it = undo.rbegin(); it != undo.rend(); ++it)
            ::rename(it->second.c_str(), it->first.c_str());
        ::unlink(journal.c_str());
        throw;
    }
    syncDir(m_dir);
    step(steps);
    ::unlink(journal.c_str());
    step(steps);
    removeStage(m_stage);
}

std::vector<std::string> COutputDir::stagedNames() const {
    std::vector<std::string> v;
    for (const auto& s : m_staged)
        v.push_back(s.second);
    return v;
}

}  // namespace risknav::common
