#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace risknav::common {
namespace {
std::string tempName(const fs::path& finalPath) {
    // The extension stays last: OpenCV picks the image format from it.
    return (finalPath.parent_path() /
            (".tmp-" + std::to_string(::getpid()) + "-" + finalPath.filename().string()))
        .string();
}

// A temporary ".tmp-<pid>-<name>" of a process that no longer exists.
bool staleTemporary(const fs::path& p) {
    const std::string n = p.filename().string();
    if (n.rfind(".tmp-", 0) != 0)
        return false;
    const auto dash = n.find('-', 5);
    if (dash == std::string::npos || dash == 5)
        return false;
    const std::string pid = n.substr(5, dash - 5);
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9)
        return false;
    const long id = std::stol(pid);
    return id != long(::getpid()) && !fs::exists("/proc/" + pid);
}

/** Files of the previous run listed in a manifest; only plain names of
 * files in the folder itself count (a run writes no others): a name with a
 * '/' (absolute, "..", a subfolder, or through a symlinked one) or a hidden
 * one is ignored: the manifest is data. */
std::vector<std::string> manifestFiles(const fs::path& manifest) {
    std::vector<std::string> files;
    std::ifstream f(manifest);
    std::string line;
    while (std::getline(f, line)) {
        if (line.rfind("file ", 0) != 0)
            continue;
        const std::string name = line.substr(5);
        if (name.empty() || name[0] == '.' || name.find('/') != std::string::npos)
            continue;
        files.push_back(name);
    }
    return files;
}

void writeWhole(const std::string& path, const std::string& content) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << content;
    f.close();
    if (!f)
        throw std::runtime_error("cannot write " + path);
}
}  // namespace

COutputDir::COutputDir(const std::string& dir, const std::string& app)
    : m_dir(dir), m_app(app) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir))
        throw CBadInputError(dir + ": cannot create the output folder" +
                             (ec ? " (" + ec.message() + ")" : std::string()));
    const std::string probe = tempName(fs::path(dir) / "write-probe");
    std::ofstream f(probe);
    if (!f.good())
        throw CBadInputError(dir + ": output folder is not writable");
    f.close();
    fs::remove(probe, ec);
    // One run per folder at a time: a lock on the folder itself (no file to
    // leave behind; the lock dies with the process).
    m_lockFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (m_lockFd < 0)
        throw CBadInputError(dir + ": cannot open the output folder");
    if (::flock(m_lockFd, LOCK_EX | LOCK_NB) != 0) {
        ::close(m_lockFd);
        m_lockFd = -1;
        throw CBadInputError(dir +
                             ": the output folder is in use by another risknav run");
    }
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        if (e.is_symlink(ec) || !staleTemporary(e.path()))
            continue;
        if (e.is_regular_file(ec))
            fs::remove(e.path(), ec);
        else if (e.is_directory(ec))  // e.g. risknav-navigate's navlog scratch folder
            fs::remove_all(e.path(), ec);
    }
}

COutputDir::~COutputDir() {
    std::error_code ec;
    if (!m_committed)
        for (const auto& [tmp, fin] : m_staged)
            fs::remove(tmp, ec);
    if (m_lockFd >= 0)
        ::close(m_lockFd);
}

std::string COutputDir::finalPath(const std::string& name) const {
    return (fs::path(m_dir) / name).string();
}

std::string COutputDir::stage(const std::string& name) {
    const std::string fin = finalPath(name);
    for (const auto& s : m_staged)
        if (s.second == fin)
            return s.first;
    m_staged.emplace_back(tempName(fin), fin);
    return m_staged.back().first;
}

void COutputDir::writeText(const std::string& name, const std::string& content) {
    writeWhole(stage(name), content);
}

void COutputDir::commitInto(const std::string& sub) {
    m_sub = sub;
}

void COutputDir::commit() {
    std::error_code ec;
    if (!m_sub.empty()) {
        const fs::path folder = fs::path(m_dir) / m_sub;
        fs::remove_all(folder, ec);
        fs::create_directories(folder, ec);
        if (!fs::is_directory(folder))
            throw std::runtime_error("cannot create " + folder.string());
    }
    // The run's files appear as one set: earlier files of the same names are
    // first moved aside, then the new ones renamed in; if any step fails,
    // everything is put back as it was.
    std::vector<std::pair<std::string, std::string>> placed,
        asideOf;  // (tmp, fin), (aside, fin)
    // A commit into the folder itself replaces the previous run's whole set:
    // its files this run does not write go aside with the replaced ones.
    std::vector<std::string> dropped;
    if (m_sub.empty()) {
        std::string manifest = "risknav output manifest 1\napp " + m_app + "\n";
        for (const auto& s : m_staged)
            manifest +=
                "file " + fs::path(s.second).lexically_relative(m_dir).string() + "\n";
        writeWhole(stage(kManifest), manifest);
        for (const auto& name : manifestFiles(fs::path(m_dir) / kManifest)) {
            const std::string fin = finalPath(name);
            bool ours = false;
            for (const auto& s : m_staged)
                ours = ours || s.second == fin;
            // the entry itself a regular file: a symlink (to a file
            // anywhere) is not the run's
            if (!ours && fs::is_regular_file(fs::symlink_status(fin, ec)))
                dropped.push_back(fin);
        }
    }
    auto rollback = [&] {
        std::error_code e2;
        for (auto it = placed.rbegin(); it != placed.rend(); ++it)
            fs::rename(it->second, it->first, e2);
        for (const auto& [aside, fin] : asideOf)
            fs::rename(aside, fin, e2);
    };
    for (const auto& [tmp, finName] : m_staged) {
        const std::string fin =
            m_sub.empty()
                ? finName
                : (fs::path(m_dir) / m_sub / fs::path(finName).filename()).string();
        if (fs::exists(fin, ec)) {
            const std::string aside =
                tempName(fs::path(fin).parent_path() /
                         ("old-" + fs::path(fin).filename().string()));
            fs::rename(fin, aside, ec);
            if (ec) {
                rollback();
                throw std::runtime_error("cannot replace " + fin + ": " + ec.message());
            }
            asideOf.emplace_back(aside, fin);
        }
        fs::rename(tmp, fin, ec);
        if (ec) {
            rollback();
            throw std::runtime_error("cannot rename " + tmp + " to " + fin + ": " +
                                     ec.message());
        }
        placed.emplace_back(tmp, fin);
    }
    for (const auto& fin : dropped) {
        const std::string aside = tempName(fs::path(fin).parent_path() /
                                           ("old-" + fs::path(fin).filename().string()));
        fs::rename(fin, aside, ec);
        if (ec) {
            rollback();
            throw std::runtime_error("cannot remove " + fin + ": " + ec.message());
        }
        asideOf.emplace_back(aside, fin);
    }
    for (const auto& [aside, fin] : asideOf)
        fs::remove(aside, ec);
    m_committed = true;
}

std::vector<std::string> COutputDir::stagedNames() const {
    std::vector<std::string> v;
    for (const auto& s : m_staged)
        v.push_back(fs::path(s.second).lexically_relative(m_dir).string());
    return v;
}

void writeFileAtomic(const std::string& path, const std::string& content) {
    const std::string tmp = tempName(fs::path(path));
    writeWhole(tmp, content);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error("cannot write " + path);
    }
}

}  // namespace risknav::common
