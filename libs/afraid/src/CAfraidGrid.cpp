#include <risknav/afraid/CAfraidGrid.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace risknav::afraid {
namespace {
const char kMagic[8] = {'R', 'N', 'A', 'F', 'R', 'A', 'I', 'D'};

template <class T>
void put(mrpt::io::CFileGZOutputStream& f, const T& v) {
    if (f.Write(&v, sizeof(T)) != sizeof(T))
        throw std::runtime_error("write failed");
}
template <class T>
T get(mrpt::io::CFileGZInputStream& f, const std::string& path) {
    T v{};
    if (f.Read(&v, sizeof(T)) != sizeof(T))
        throw std::runtime_error(path + ": truncated .afraid file");
    return v;
}
void putSparse(mrpt::io::CFileGZOutputStream& f, const std::vector<uint32_t>& v) {
    uint32_t n = 0;
    for (uint32_t x : v)
        n += x != 0;
    put(f, n);
    for (uint32_t i = 0; i < v.size(); i++)
        if (v[i]) {
            put(f, i);
            put(f, v[i]);
        }
}
void getSparse(mrpt::io::CFileGZInputStream& f, std::vector<uint32_t>& v,
               const std::string& path) {
    const uint32_t n = get<uint32_t>(f, path);
    if (n > v.size())
        throw std::runtime_error(path + ": corrupt .afraid file (cell count)");
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t i = get<uint32_t>(f, path), x = get<uint32_t>(f, path);
        if (i >= v.size())
            throw std::runtime_error(path + ": corrupt .afraid file (cell index)");
        v[i] = x;
    }
}
}  // namespace

CAfraidGrid::CAfraidGrid(const mrpt::maps::COccupancyGridMap2D& map)
    : m_xmin(map.getXMin()),
      m_ymin(map.getYMin()),
      m_res(map.getResolution()),
      m_sx(int(map.getSizeX())),
      m_sy(int(map.getSizeY())),
      m_exposure(size_t(m_sx) * m_sy, 0),
      m_robotEvents(size_t(m_sx) * m_sy, 0),
      m_obstacleEvents(size_t(m_sx) * m_sy, 0) {}

bool CAfraidGrid::sameGeometry(const CAfraidGrid& o) const {
    return m_sx == o.m_sx && m_sy == o.m_sy && std::abs(m_res - o.m_res) < 1e-6 &&
           std::abs(m_xmin - o.m_xmin) < 1e-4 && std::abs(m_ymin - o.m_ymin) < 1e-4;
}

std::string CAfraidGrid::geometryText() const {
    char b[160];
    std::snprintf(b, sizeof(b), "%d x %d cells of %.3f m from (%.2f, %.2f)", m_sx, m_sy,
                  m_res, m_xmin, m_ymin);
    return b;
}

int CAfraidGrid::xToCol(double x) const {
    return int(std::floor((x - m_xmin) / m_res));
}
int CAfraidGrid::yToRow(double y) const {
    return int(std::floor((y - m_ymin) / m_res));
}

size_t CAfraidGrid::index(double x, double y, bool& ok) const {
    const int cx = xToCol(x), cy = yToRow(y);
    ok = inside(cx, cy);
    return ok ? size_t(cy) * m_sx + cx : 0;
}

void CAfraidGrid::addExposure(double x, double y) {
    bool ok;
    const size_t i = index(x, y, ok);
    if (ok)
        m_exposure[i]++;
}
void CAfraidGrid::addRobotEvent(double x, double y) {
    bool ok;
    const size_t i = index(x, y, ok);
    if (ok)
        m_robotEvents[i]++;
}
void CAfraidGrid::addObstacleEvent(double x, double y) {
    bool ok;
    const size_t i = index(x, y, ok);
    if (ok)
        m_obstacleEvents[i]++;
}

uint64_t CAfraidGrid::totalRobotEvents() const {
    uint64_t n = 0;
    for (uint32_t v : m_robotEvents)
        n += v;
    return n;
}

void CAfraidGrid::merge(const CAfraidGrid& o) {
    if (!sameGeometry(o))
        throw std::runtime_error("the .afraid file was learned on another map (" +
                                 o.geometryText() + "; this map: " + geometryText() +
                                 ")");
    for (size_t i = 0; i < m_exposure.size(); i++) {
        m_exposure[i] += o.m_exposure[i];
        m_robotEvents[i] += o.m_robotEvents[i];
        m_obstacleEvents[i] += o.m_obstacleEvents[i];
    }
    runs += o.runs;
    frames += o.frames;
}

void CAfraidGrid::save(const std::string& path) const {
    const std::filesystem::path p(path);
    const std::string tmp = (p.parent_path() / (".tmp-" + std::to_string(::getpid()) +
                                                "-" + p.filename().string()))
                                .string();
    {
        mrpt::io::CFileGZOutputStream f;
        if (!f.open(tmp, 6))
            throw std::runtime_error("cannot write " + path);
        f.Write(kMagic, 8);
        put(f, kVersion);
        put(f, m_xmin);
        put(f, m_ymin);
        put(f, m_res);
        put(f, int32_t(m_sx));
        put(f, int32_t(m_sy));
        put(f, runs);
        put(f, frames);
        putSparse(f, m_exposure);
        putSparse(f, m_robotEvents);
        putSparse(f, m_obstacleEvents);
        f.close();
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error("cannot write " + path);
    }
}

CAfraidGrid CAfraidGrid::load(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw std::runtime_error(path + ": .afraid file not found");
    mrpt::io::CFileGZInputStream f;
    if (!f.open(path))
        throw std::runtime_error(path + ": cannot read the .afraid file");
    char magic[8] = {};
    if (f.Read(magic, 8) != 8 || std::memcmp(magic, kMagic, 8) != 0)
        throw std::runtime_error(path + ": not a risknav .afraid file");
    const uint32_t version = get<uint32_t>(f, path);
    if (version != kVersion)
        throw std::runtime_error(path + ": .afraid file version " +
                                 std::to_string(version) + " (this build reads " +
                                 std::to_string(kVersion) + ")");
    CAfraidGrid g;
    g.m_xmin = get<double>(f, path);
    g.m_ymin = get<double>(f, path);
    g.m_res = get<double>(f, path);
    g.m_sx = get<int32_t>(f, path);
    g.m_sy = get<int32_t>(f, path);
    if (g.m_sx <= 0 || g.m_sy <= 0 || g.m_sx > 100000 || g.m_sy > 100000 ||
        !(g.m_res > 0))
        throw std::runtime_error(path + ": corrupt .afraid file (geometry)");
    g.runs = get<uint32_t>(f, path);
    g.frames = get<uint64_t>(f, path);
    const size_t n = size_t(g.m_sx) * g.m_sy;
    g.m_exposure.assign(n, 0);
    g.m_robotEvents.assign(n, 0);
    g.m_obstacleEvents.assign(n, 0);
    getSparse(f, g.m_exposure, path);
    getSparse(f, g.m_robotEvents, path);
    getSparse(f, g.m_obstacleEvents, path);
    return g;
}

}  // namespace risknav::afraid
