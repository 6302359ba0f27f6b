#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>

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

void writeWhole(const std::string& path, const std::string& content) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << content;
    f.close();
    if (!f)
        throw std::runtime_error("cannot write " + path);
}
}  // namespace

COutputDir::COutputDir(const std::string& dir) : m_dir(dir) {
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
}

COutputDir::~COutputDir() {
    if (m_committed)
        return;
    std::error_code ec;
    for (const auto& [tmp, fin] : m_staged)
        fs::remove(tmp, ec);
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

void COutputDir::commit() {
    for (const auto& [tmp, fin] : m_staged) {
        std::error_code ec;
        fs::rename(tmp, fin, ec);
        if (ec)
            throw std::runtime_error("cannot rename " + tmp + " to " + fin + ": " +
                                     ec.message());
    }
    m_committed = true;
}

std::vector<std::string> COutputDir::stagedNames() const {
    std::vector<std::string> v;
    for (const auto& s : m_staged)
        v.push_back(fs::path(s.second).filename().string());
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
