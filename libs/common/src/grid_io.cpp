#include <risknav/common/CBadInputError.h>
#include <risknav/common/COutputDir.h>
#include <risknav/common/config_read.h>
#include <risknav/common/grid_io.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/serialization/CArchive.h>

#include <opencv2/imgcodecs.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using mrpt::maps::COccupancyGridMap2D;

namespace risknav::common {
void TMapSourceOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                           const std::string& s) {
    section = s;
    map_file = readPath(c, s, "map_file", map_file, true);
    map_resolution = readDouble(c, s, "map_resolution", map_resolution);
    map_origin_x = readDouble(c, s, "map_origin_x", map_origin_x);
    map_origin_y = readDouble(c, s, "map_origin_y", map_origin_y);
    simplemap_resolution = readDouble(c, s, "simplemap_resolution", simplemap_resolution);
}

void TMapSourceOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                         const std::string& s) const {
    writeKey(c, s, "map_file", map_file);
    writeKey(c, s, "map_resolution", map_resolution);
    writeKey(c, s, "map_origin_x", map_origin_x);
    writeKey(c, s, "map_origin_y", map_origin_y);
    writeKey(c, s, "simplemap_resolution", simplemap_resolution);
}

void TMapSourceOptions::validate() const {
    checkRule(!map_file.empty(), section, "map_file", map_file, "required");
    checkKey(section, "map_resolution", map_resolution, TRange::closed(0.001, 10, "m"));
    // Beyond a million metres MRPT's grid index arithmetic loses its cells.
    checkKey(section, "map_origin_x", map_origin_x, TRange::closed(-1e6, 1e6, "m"));
    checkKey(section, "map_origin_y", map_origin_y, TRange::closed(-1e6, 1e6, "m"));
    checkKey(section, "simplemap_resolution", simplemap_resolution,
             TRange::closed(0.001, 10, "m"));
}

namespace {
// Keeps a decoder's own messages (libpng: "libpng error: Read Error") off
// stderr while it runs: the app reports the failure in its one line.
class CStderrSilenced {
  public:
    CStderrSilenced() {
        std::fflush(stderr);
        m_saved = ::dup(2);
        const int devnull = ::open("/dev/null", O_WRONLY);
        if (devnull >= 0) {
            ::dup2(devnull, 2);
            ::close(devnull);
        }
    }
    ~CStderrSilenced() {
        std::fflush(stderr);
        if (m_saved >= 0) {
            ::dup2(m_saved, 2);
            ::close(m_saved);
        }
    }
    CStderrSilenced(const CStderrSilenced&) = delete;
    CStderrSilenced& operator=(const CStderrSilenced&) = delete;

  private:
    int m_saved = -1;
};

bool endsWith(std::string s, const std::string& suffix) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char ch) { return std::tolower(ch); });
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

enum class TPixelModel {
    FreeIsWhite,  // P(free) = grey/255 (MRPT bitmaps)
    RosTrinary,
    RosScale
};

struct TRosParams {
    double occupied = 0.65, free = 0.196;
    bool negate = false;
};

// The largest grid risknav reads (cells): 25 M, e.g. 250 m x 250 m at 5 cm.
constexpr uint64_t kMaxGridCells = 25'000'000;

/** The pixel size of a PNG, BMP or binary/ASCII PGM from its header, without
 * decoding it (0 x 0: not one of those, left to the decoder). */
std::pair<uint64_t, uint64_t> imageHeaderSize(const std::string& file) {
    std::ifstream f(file, std::ios::binary);
    unsigned char h[64] = {};
    f.read(reinterpret_cast<char*>(h), sizeof(h));
    const auto n = size_t(f.gcount());
    auto be32 = [&](size_t o) {
        return uint64_t(h[o]) << 24 | uint64_t(h[o + 1]) << 16 | uint64_t(h[o + 2]) << 8 |
               uint64_t(h[o + 3]);
    };
    auto le32 = [&](size_t o) {
        return uint64_t(uint32_t(h[o] | h[o + 1] << 8 | h[o + 2] << 16 | h[o + 3] << 24));
    };
    if (n >= 24 && h[0] == 0x89 && h[1] == 'P' && h[2] == 'N' && h[3] == 'G')
        return {be32(16), be32(20)};
    if (n >= 26 && h[0] == 'B' && h[1] == 'M') {
        const int64_t w = int32_t(le32(18)), hh = int32_t(le32(22));
        return {uint64_t(std::abs(w)), uint64_t(std::abs(hh))};
    }
    if (n >= 2 && h[0] == 'P' && (h[1] == '2' || h[1] == '5')) {
        // "P5 <w> <h> ...", comments (#...) between the fields
        std::string t(reinterpret_cast<char*>(h) + 2, n - 2);
        std::vector<uint64_t> v;
        size_t i = 0;
        while (v.size() < 2 && i < t.size()) {
            if (t[i] == '#') {
                while (i < t.size() && t[i] != '\n')
                    i++;
            } else if (std::isdigit(static_cast<unsigned char>(t[i]))) {
                uint64_t x = 0;
                while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i])) &&
                       x < (uint64_t(1) << 40))
                    x = x * 10 + uint64_t(t[i++] - '0');
                v.push_back(x);
                continue;
            }
            i++;
        }
        if (v.size() == 2)
            return {v[0], v[1]};
    }
    return {0, 0};
}

COccupancyGridMap2D fromImage(const std::string& file, double res, double ox, double oy,
                              TPixelModel model, const TRosParams& ros = {}) {
    // before decoding: a small file can hold a huge image (a 439 KB PNG of
    // 20000 x 20000 px took 4.4 GB)
    if (const auto [w, h] = imageHeaderSize(file); w * h > kMaxGridCells)
        throw CBadInputError(file + ": the map image is " + std::to_string(w) + " x " +
                             std::to_string(h) + " px, more than " +
                             std::to_string(kMaxGridCells / 1000000) +
                             " M cells (one cell per pixel)");
    cv::Mat img;
    try {
        const CStderrSilenced quiet;  // libpng prints its own lines on a bad file
        img = cv::imread(file, cv::IMREAD_GRAYSCALE);
    } catch (const std::exception&) {
    }
    if (img.empty())
        throw CBadInputError(file + ": cannot read the map image (not a PNG/PGM/BMP?)");
    if (img.cols < 2 || img.rows < 2)
        throw CBadInputError(file + ": map image is too small (" +
                             std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                             " px)");
    COccupancyGridMap2D g;
    // Cell centres: the grid spans exactly the image (cols*res by rows*res).
    g.setSize(static_cast<float>(ox), static_cast<float>(ox + img.cols * res),
              static_cast<float>(oy), static_cast<float>(oy + img.rows * res),
              static_cast<float>(res), 0.5f);
    const int nx = static_cast<int>(g.getSizeX()), ny = static_cast<int>(g.getSizeY());
    for (int cy = 0; cy < ny; cy++) {
        const int row = img.rows - 1 - std::min(cy, img.rows - 1);  // image row 0 = top
        const uint8_t* p = img.ptr<uint8_t>(row);
        for (int cx = 0; cx < nx; cx++) {
            const double grey = p[std::min(cx, img.cols - 1)] / 255.0;
            double pfree = grey;
            if (model != TPixelModel::FreeIsWhite) {
                const double occ = ros.negate ? grey : 1.0 - grey;
                if (model == TPixelModel::RosScale)
                    pfree = 1.0 - occ;
                else
                    pfree = occ > ros.occupied ? 0.0 : (occ < ros.free ? 1.0 : 0.5);
            }
            g.setCell(cx, cy, static_cast<float>(pfree));
        }
    }
    return g;
}

// ROS map_server YAML is flat "key: value"; a full YAML parser would accept
// more, but these are all the keys map_server defines.
COccupancyGridMap2D fromRosYaml(const std::string& file) {
    std::ifstream f(file);
    if (!f.good())
        throw CBadInputError(file + ": cannot read the map YAML");
    std::map<std::string, std::string> kv;
    std::string line;
    while (std::getline(f, line)) {
        line = line.substr(0, line.find('#'));
        const auto colon = line.find(':');
        if (colon == std::string::npos)
            continue;
        auto trim = [](std::string s) {
            s.erase(0, s.find_first_not_of(" \t\r\"'"));
            s.erase(s.find_last_not_of(" \t\r\"'") + 1);
            return s;
        };
        kv[trim(line.substr(0, colon))] = trim(line.substr(colon + 1));
    }
    auto need = [&](const std::string& k) {
        if (!kv.count(k) || kv[k].empty())
            throw CBadInputError(file + ": map YAML has no '" + k + "' key");
        return kv[k];
    };
    auto number = [&](const std::string& k, const std::string& v) {
        char* end = nullptr;
        const double d = std::strtod(v.c_str(), &end);
        if (v.empty() || *end != '\0')
            throw CBadInputError(file + ": map YAML key '" + k + "' = '" + v +
                                 "' is not a number");
        return d;
    };
    fs::path img = need("image");
    if (img.is_relative())
        img = fs::path(file).parent_path() / img;
    const double res = number("resolution", need("resolution"));
    if (!(res >= 0.001 && res <= 10))
        throw CBadInputError(file + ": map YAML resolution '" + need("resolution") +
                             "' must be in [0.001, 10] m");
    std::string o = need("origin");
    std::replace(o.begin(), o.end(), '[', ' ');
    std::replace(o.begin(), o.end(), ']', ' ');
    std::replace(o.begin(), o.end(), ',', ' ');
    std::istringstream os(o);
    double ox = 0, oy = 0, oyaw = 0;
    if (!(os >> ox >> oy))
        throw CBadInputError(file + ": map YAML origin must be [x, y, yaw]");
    if (!(std::abs(ox) <= 1e6 && std::abs(oy) <= 1e6))
        throw CBadInputError(file + ": map YAML origin x, y must be in [-1e6, 1e6] m");
    os >> oyaw;
    if (oyaw != 0.0)
        throw CBadInputError(file + ": map YAML origin yaw != 0 is not supported");
    TRosParams rp;
    if (kv.count("occupied_thresh"))
        rp.occupied = number("occupied_thresh", kv["occupied_thresh"]);
    if (kv.count("free_thresh"))
        rp.free = number("free_thresh", kv["free_thresh"]);
    // map_server's thresholds are probabilities in [0, 1], free below occupied;
    // anything else (nan, inf, 2) would silently turn every wall into unknown.
    for (const auto& [k, v] :
         {std::pair{"occupied_thresh", rp.occupied}, std::pair{"free_thresh", rp.free}})
        if (!(v >= 0 && v <= 1))
            throw CBadInputError(file + ": map YAML " + k + " = '" + kv[k] +
                                 "' must be in [0, 1]");
    if (!(rp.free < rp.occupied))
        throw CBadInputError(file + ": map YAML free_thresh must be < occupied_thresh");
    if (kv.count("negate")) {
        const std::string n = kv["negate"];
        if (n != "0" && n != "1" && n != "true" && n != "false")
            throw CBadInputError(file + ": map YAML negate = '" + n + "' must be 0 or 1");
        rp.negate = n == "1" || n == "true";
    }
    const std::string mode = kv.count("mode") ? kv["mode"] : "trinary";
    if (mode != "trinary" && mode != "scale")
        throw CBadInputError(file + ": map YAML mode '" + mode +
                             "' is not supported (trinary, scale)");
    if (const std::string why = fileProblem(img.string()); !why.empty())
        throw CBadInputError(file + ": map image " + why + ": " + img.string());
    return fromImage(img.string(), res, ox, oy,
                     mode == "scale" ? TPixelModel::RosScale : TPixelModel::RosTrinary,
                     rp);
}

// A .gridmap is MRPT's serialized COccupancyGridMap2D. Its header (class name,
// version 6: bits per cell, size_x, size_y, bounds, resolution) is checked
// BEFORE MRPT deserializes it: a corrupt header (zeroed, resolution 0, huge
// sizes) made MRPT allocate gigabytes. The file is decompressed into memory
// no further than the largest grid needs.
COccupancyGridMap2D fromGridmap(const std::string& file) {
    std::string bytes;
    try {
        mrpt::io::CFileGZInputStream f(file);
        const size_t cap = size_t(kMaxGridCells) + (1u << 20);
        char buf[1 << 16];
        for (size_t n; (n = f.Read(buf, sizeof(buf))) > 0;) {
            bytes.append(buf, n);
            if (bytes.size() > cap)
                throw CBadInputError(file +
                                     ": larger than the largest map risknav reads (" +
                                     std::to_string(kMaxGridCells) + " cells)");
        }
    } catch (const CBadInputError&) {
        throw;
    } catch (const std::exception&) {
        throw CBadInputError(file + ": not a readable MRPT .gridmap file");
    }
    const std::string name = "mrpt::maps::COccupancyGridMap2D";
    const size_t h = 1 + name.size();  // length byte (0x80 | len) + class name
    const size_t o = h + 2;            // after the version and the bits-per-cell byte
    auto bad = [&](const std::string& why) {
        return CBadInputError(file + ": not a readable MRPT .gridmap file (" + why + ")");
    };
    if (bytes.size() < o + 28 || uint8_t(bytes[0]) != (0x80 | name.size()) ||
        bytes.compare(1, name.size(), name) != 0)
        throw bad("no COccupancyGridMap2D header");
    // Only the layout MRPT 2.5 writes (version 6, 8-bit cells) is read.
    if (uint8_t(bytes[h]) != 6)
        throw bad("serialization version " + std::to_string(uint8_t(bytes[h])) +
                  "; MRPT 2.5 writes 6");
    if (uint8_t(bytes[h + 1]) != 8 * sizeof(COccupancyGridMap2D::cellType))
        throw bad("cells of " + std::to_string(uint8_t(bytes[h + 1])) + " bits");
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        for (int k = 3; k >= 0; k--)
            v = (v << 8) | uint8_t(bytes[at + size_t(k)]);
        return v;
    };
    auto f32 = [&](size_t at) {
        const uint32_t u = u32(at);
        float v;
        std::memcpy(&v, &u, 4);
        return v;
    };
    const uint64_t sx = u32(o), sy = u32(o + 4);
    const double x0 = f32(o + 8), x1 = f32(o + 12), y0 = f32(o + 16), y1 = f32(o + 20),
                 res = f32(o + 24);
    if (!(res >= 0.001 && res <= 10))
        throw bad("resolution " + std::to_string(res) + " m");
    if (!(std::abs(x0) <= 1e6 && std::abs(x1) <= 1e6 && std::abs(y0) <= 1e6 &&
          std::abs(y1) <= 1e6 && x0 < x1 && y0 < y1))
        throw bad("map bounds");
    if (sx == 0 || sy == 0 || sx * sy > kMaxGridCells)
        throw bad(std::to_string(sx) + " x " + std::to_string(sy) + " cells");
    if (sx * sy > bytes.size() - (o + 28))
        throw bad("truncated: " + std::to_string(sx) + " x " + std::to_string(sy) +
                  " cells announced");
    // The grid is built from the checked header and its cells; the options
    // MRPT stores after the cells (insertion / likelihood settings, which
    // risknav sets itself) are not read: their lengths come from the file
    // too, and a corrupt one made MRPT allocate gigabytes.
    COccupancyGridMap2D g;
    g.setSize(float(x0), float(x1), float(y0), float(y1), float(res));
    if (g.getSizeX() != sx || g.getSizeY() != sy)
        throw bad("size " + std::to_string(sx) + " x " + std::to_string(sy) +
                  " does not match its bounds and resolution");
    const char* cells = bytes.data() + o + 28;
    for (uint64_t cy = 0; cy < sy; cy++)
        std::memcpy(g.getRow(int(cy)), cells + cy * sx, size_t(sx));
    return g;
}

COccupancyGridMap2D fromSimplemap(const std::string& file, double res) {
    mrpt::maps::CSimpleMap sm;
    try {
        if (!sm.loadFromFile(file))
            throw std::runtime_error("load");
    } catch (const std::exception&) {
        throw CBadInputError(file + ": not a readable MRPT .simplemap file");
    }
    if (sm.empty())
        throw CBadInputError(file + ": the simplemap has no keyframes");
    COccupancyGridMap2D g(-10, 10, -10, 10, static_cast<float>(res));
    g.loadFromSimpleMap(sm);
    return g;
}
}  // namespace

mrpt::maps::COccupancyGridMap2D loadOccupancyGrid(const TMapSourceOptions& src) {
    const std::string& f = src.map_file;
    if (const std::string why = fileProblem(f); !why.empty())
        throw CBadInputError(f + ": map file " + why);
    COccupancyGridMap2D g;
    if (endsWith(f, ".gridmap") || endsWith(f, ".gridmap.gz"))
        g = fromGridmap(f);
    else if (endsWith(f, ".yaml") || endsWith(f, ".yml"))
        g = fromRosYaml(f);
    else if (endsWith(f, ".simplemap") || endsWith(f, ".simplemap.gz"))
        g = fromSimplemap(f, src.simplemap_resolution);
    else
        g = fromImage(f, src.map_resolution, src.map_origin_x, src.map_origin_y,
                      TPixelModel::FreeIsWhite);
    if (g.getSizeX() < 2 || g.getSizeY() < 2)
        throw CBadInputError(f + ": the map is empty");
    return g;
}

void saveGridmapGz(const mrpt::maps::COccupancyGridMap2D& g, const std::string& path) {
    try {
        mrpt::io::CFileGZOutputStream f(path);
        auto a = mrpt::serialization::archiveFrom(f);
        a << g;
    } catch (const std::exception&) {
        // MRPT says only "Cannot write bytes to stream!": name the file.
        throw writeFailure(path, errno);
    }
}

}  // namespace risknav::common
