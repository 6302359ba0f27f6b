#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/config_read.h>

#include <mrpt/io/CFileGZInputStream.h>

#include <mrpt/io/CFileGZOutputStream.h>
#include <fstream>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace risknav::afraid {
using common::CBadInputError;

namespace {
const char kMagic[8] = {'R', 'N', 'A', 'F', 'R', 'A', 'I', 'D'};
constexpr size_t kHeaderBytes = 56;  // magic .. frames (see CAfraidGrid.h)
static_assert(std::numeric_limits<double>::is_iec559, "IEEE-754 doubles required");

// Little-endian encoding, byte by byte (independent of the host's order).
void putU32(std::string& b, uint32_t v) {
    for (int k = 0; k < 4; k++)
        b.push_back(char(uint8_t(v >> (8 * k))));
}
void putU64(std::string& b, uint64_t v) {
    for (int k = 0; k < 8; k++)
        b.push_back(char(uint8_t(v >> (8 * k))));
}
void putF64(std::string& b, double v) {
    uint64_t u;
    std::memcpy(&u, &v, 8);
    putU64(b, u);
}
void putSparse(std::string& b, const std::vector<uint32_t>& v) {
    uint32_t n = 0;
    for (uint32_t x : v)
        n += x != 0;
    putU32(b, n);
    for (uint32_t i = 0; i < v.size(); i++)
        if (v[i]) {
            putU32(b, i);
            putU32(b, v[i]);
        }
}

// Little-endian decoding from a byte buffer; every error names the file.
class CLeReader {
  public:
    CLeReader(const std::string& bytes, const std::string& name)
        : m_b(bytes), m_name(name) {}
    size_t remaining() const { return m_b.size() - m_pos; }
    [[noreturn]] void fail(const std::string& what) const {
        throw CBadInputError(m_name + ": " + what);
    }
    uint64_t uint(int n) {
        if (remaining() < size_t(n))
            fail("truncated .afraid file");
        uint64_t v = 0;
        for (int k = 0; k < n; k++)
            v |= uint64_t(uint8_t(m_b[m_pos + size_t(k)])) << (8 * k);
        m_pos += size_t(n);
        return v;
    }
    uint32_t u32() { return uint32_t(uint(4)); }
    int32_t i32() {
        const uint32_t u = u32();
        int32_t v;
        std::memcpy(&v, &u, 4);
        return v;
    }
    uint64_t u64() { return uint(8); }
    double f64() {
        const uint64_t u = u64();
        double v;
        std::memcpy(&v, &u, 8);
        return v;
    }

  private:
    const std::string& m_b;
    const std::string& m_name;
    size_t m_pos = 0;
};

// One sparse layer as (cell index, count) pairs; n is checked against the
// bytes left before anything is reserved.
std::vector<std::pair<uint32_t, uint32_t>> getSparse(CLeReader& r, uint64_t cells,
                                                     uint32_t version) {
    const uint32_t n = r.u32();
    if (n > cells)
        r.fail("corrupt .afraid file (cell count " + std::to_string(n) + " > " +
               std::to_string(cells) + " cells)");
    if (uint64_t(n) * 8 > r.remaining())
        r.fail("truncated .afraid file (" + std::to_string(n) + " cells announced, " +
               std::to_string(r.remaining()) + " bytes left)");
    std::vector<std::pair<uint32_t, uint32_t>> v;
    v.reserve(n);
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t i = r.u32(), x = r.u32();
        if (i >= cells)
            r.fail("corrupt .afraid file (cell index)");
        if (version >= 2 && ((!v.empty() && i <= v.back().first) || x == 0))
            r.fail("corrupt .afraid file (cell order)");
        v.emplace_back(i, x);
    }
    return v;
}

std::string geometryError(int sx, int sy) {
    return "map of " + std::to_string(sx) + " x " + std::to_string(sy) +
           " cells, more than an afraid grid holds (" +
           std::to_string(CAfraidGrid::kMaxCells) + " cells)";
}

// The fixed-size header, read and checked: magic, version, geometry.
struct THeader {
    uint32_t version = 0;
    double xmin = 0, ymin = 0, res = 0;
    int32_t sx = 0, sy = 0;
    uint32_t runs = 0;
    uint64_t frames = 0;
    uint64_t cells() const { return uint64_t(sx) * uint64_t(sy); }
    // The decompressed size a file with this header can legitimately have.
    uint64_t maxBytes() const {
        return kHeaderBytes + (version >= 3 ? 4 : 3) * (4 + 8 * cells());
    }
};
THeader getHeader(CLeReader& r, const std::string& bytes) {
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 8) != 0)
        r.fail("not a risknav .afraid file");
    r.u64();  // the magic
    THeader h;
    h.version = r.u32();
    if (h.version < CAfraidGrid::kOldestVersion || h.version > CAfraidGrid::kVersion)
        r.fail(".afraid file version " + std::to_string(h.version) +
               " (this build reads " + std::to_string(CAfraidGrid::kOldestVersion) +
               " to " + std::to_string(CAfraidGrid::kVersion) + ")");
    h.xmin = r.f64();
    h.ymin = r.f64();
    h.res = r.f64();
    h.sx = r.i32();
    h.sy = r.i32();
    if (h.sx <= 0 || h.sy <= 0 || !std::isfinite(h.xmin) || !std::isfinite(h.ymin) ||
        !std::isfinite(h.res) || !(h.res > 0))
        r.fail("corrupt .afraid file (geometry)");
    if (h.cells() > CAfraidGrid::kMaxCells)
        r.fail(geometryError(h.sx, h.sy));
    h.runs = r.u32();
    h.frames = r.u64();
    return h;
}
}  // namespace

CAfraidGrid::CAfraidGrid(const mrpt::maps::COccupancyGridMap2D& map)
    : m_xmin(map.getXMin()),
      m_ymin(map.getYMin()),
      m_res(map.getResolution()),
      m_sx(int(map.getSizeX())),
      m_sy(int(map.getSizeY())) {
    if (uint64_t(m_sx) * uint64_t(m_sy) > kMaxCells)
        throw CBadInputError(geometryError(m_sx, m_sy));
    m_exposure.assign(size_t(m_sx) * m_sy, 0);
    m_robotEvents.assign(size_t(m_sx) * m_sy, 0);
    m_obstacleEvents.assign(size_t(m_sx) * m_sy, 0);
    m_passes.assign(size_t(m_sx) * m_sy, 0);
}

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
void CAfraidGrid::addTraversal(double x0, double y0, double x1, double y1) {
    // Cells entered along the segment, by sampling at a quarter cell: a cell
    // counts when the sample moves into it from another one.
    const int c0 = xToCol(x0), r0 = yToRow(y0);
    const double L = std::hypot(x1 - x0, y1 - y0);
    const int n = int(std::ceil(L / (0.25 * m_res)));
    int pc = c0, pr = r0;
    for (int k = 1; k <= n; k++) {
        const double f = double(k) / n;
        const int c = xToCol(x0 + f * (x1 - x0)), r = yToRow(y0 + f * (y1 - y0));
        if ((c != pc || r != pr) && inside(c, r))
            m_passes[size_t(r) * m_sx + c]++;
        pc = c;
        pr = r;
    }
}
void CAfraidGrid::addPass(double x, double y) {
    bool ok;
    const size_t i = index(x, y, ok);
    if (ok)
        m_passes[i]++;
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
        m_passes[i] += o.m_passes[i];
    }
    runs += o.runs;
    frames += o.frames;
}

std::string CAfraidGrid::encode() const {
    std::string b(kMagic, 8);
    putU32(b, kVersion);
    putF64(b, m_xmin);
    putF64(b, m_ymin);
    putF64(b, m_res);
    putU32(b, uint32_t(m_sx));
    putU32(b, uint32_t(m_sy));
    putU32(b, runs);
    putU64(b, frames);
    putSparse(b, m_exposure);
    putSparse(b, m_robotEvents);
    putSparse(b, m_obstacleEvents);
    putSparse(b, m_passes);
    return b;
}

CAfraidGrid CAfraidGrid::decode(const std::string& bytes, const std::string& name) {
    CLeReader r(bytes, name);
    const THeader h = getHeader(r, bytes);
    CAfraidGrid g;
    g.m_xmin = h.xmin;
    g.m_ymin = h.ymin;
    g.m_res = h.res;
    g.m_sx = h.sx;
    g.m_sy = h.sy;
    g.runs = h.runs;
    g.frames = h.frames;
    const uint64_t cells = h.cells();
    const uint32_t version = h.version;
    const auto exposure = getSparse(r, cells, version),
               robotEvents = getSparse(r, cells, version),
               obstacleEvents = getSparse(r, cells, version);
    // Version 3 counts the cells the robot entered (passes); older files have
    // only frames, taken as passes (at the learning speeds, ~ one cell per frame).
    const auto passes = version >= 3 ? getSparse(r, cells, version) : exposure;
    if (version >= 2 && r.remaining() != 0)
        r.fail("corrupt .afraid file (" + std::to_string(r.remaining()) +
               " bytes after the data)");
    // Only now, with the whole file valid, the dense layers.
    for (auto [layer, sparse] :
         {std::pair{&g.m_exposure, &exposure}, std::pair{&g.m_robotEvents, &robotEvents},
          std::pair{&g.m_obstacleEvents, &obstacleEvents},
          std::pair{&g.m_passes, &passes}}) {
        layer->assign(size_t(cells), 0);
        for (const auto& [i, x] : *sparse)
            (*layer)[i] = x;
    }
    return g;
}

void CAfraidGrid::save(const std::string& path) const {
    const std::string tmp = common::exclusiveTempBeside(path);
    const std::string bytes = encode();
    bool ok;
    int err = 0;
    {
        mrpt::io::CFileGZOutputStream f;
        ok = f.open(tmp, 6) && f.Write(bytes.data(), bytes.size()) == bytes.size();
        err = errno;
        f.close();
    }
    std::error_code ec;
    if (ok)
        std::filesystem::rename(tmp, path, ec);
    if (!ok || ec) {
        ::unlink(tmp.c_str());
        throw common::writeFailure(path, ec ? ec.value() : err);
    }
}

CAfraidGrid CAfraidGrid::load(const std::string& path) {
    if (const std::string why = common::fileProblem(path); !why.empty())
        throw CBadInputError(path + ": .afraid file " + why);
    mrpt::io::CFileGZInputStream f;
    if (!f.open(path))
        throw CBadInputError(path + ": cannot read the .afraid file");
    // The decompressed content, the header first: it bounds the rest.
    std::string bytes;
    uint64_t limit = kHeaderBytes;
    std::vector<char> buf(1 << 16);
    while (true) {
        const size_t want =
            size_t(std::min<uint64_t>(buf.size(), limit + 1 - bytes.size()));
        size_t got = 0;
        try {
            got = f.Read(buf.data(), want);
        } catch (const std::exception&) {
            throw CBadInputError(path + ": corrupt .afraid file (gz stream)");
        }
        if (got == 0)
            break;
        // MRPT passes zlib's -1 (a bad CRC) on as a huge count
        if (got > want)
            throw CBadInputError(path + ": corrupt .afraid file (gz stream)");
        bytes.append(buf.data(), got);
        if (limit == kHeaderBytes && bytes.size() >= kHeaderBytes) {
            CLeReader r(bytes, path);
            limit = getHeader(r, bytes).maxBytes();
        }
        if (bytes.size() > limit)
            throw CBadInputError(path + ": corrupt .afraid file (longer than its " +
                                 "header allows)");
    }
    CAfraidGrid g = decode(bytes, path);
    // zlib stops at the end of a gzip stream and says nothing of bytes after
    // it: the stream's own trailer (its last 4 bytes, the data's size mod
    // 2^32) must end the file (a file that is no gzip stream zlib reads as it
    // is, and decode() judged it whole)
    {
        std::ifstream raw(path, std::ios::binary | std::ios::ate);
        const auto size = raw.tellg();
        unsigned char m[2] = {0, 0}, t[4] = {0, 0, 0, 0};
        if (size >= 4) {
            raw.seekg(0);
            raw.read(reinterpret_cast<char*>(m), 2);
            raw.seekg(size - std::streamoff(4));
            raw.read(reinterpret_cast<char*>(t), 4);
        }
        const bool gzip = m[0] == 0x1f && m[1] == 0x8b;
        const uint32_t isize = uint32_t(t[0]) | uint32_t(t[1]) << 8 |
                               uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24;
        if (gzip && (!raw || isize != uint32_t(bytes.size())))
            throw CBadInputError(path +
                                 ": corrupt .afraid file (bytes after its gz stream)");
    }
    return g;
}

}  // namespace risknav::afraid
