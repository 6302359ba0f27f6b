#include <risknav/common/CAllocationBudget.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/common/grid_io.h>

#include <yaml.h>
#include <opencv2/imgcodecs.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "grid_readers.h"

// Map images and ROS map_server YAML files (loadOccupancyGrid(), grid_io.cpp).
namespace fs = std::filesystem;
using mrpt::maps::COccupancyGridMap2D;

namespace risknav::common::grid_readers {
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

/** An image's format and pixel size from its header, without decoding it. */
struct TImageHeader {
    std::string format;  ///< empty: not a format risknav reads
    uint64_t width = 0, height = 0;
    /** PGM/PPM: the header's maximum value (white), 0 elsewhere. */
    uint64_t maxval = 0;
};

/** Reads the header of a PNG, BMP, PBM/PGM/PPM, JPEG or TIFF file (the
 * formats risknav decodes; OpenCV would decode more, but for no other is the
 * size checked before decoding, so they are refused). width/height 0: the
 * header names no size. */
TImageHeader imageHeader(const std::string& file) {
    std::ifstream f(file, std::ios::binary);
    std::string h(4096, '\0');
    f.read(&h[0], std::streamsize(h.size()));
    h.resize(size_t(f.gcount()));
    f.clear();
    const size_t n = h.size();
    auto u8 = [&](size_t o) { return o < n ? uint64_t(uint8_t(h[o])) : 0; };
    auto be16 = [&](size_t o) { return u8(o) << 8 | u8(o + 1); };
    auto be32 = [&](size_t o) { return be16(o) << 16 | be16(o + 2); };
    auto le16 = [&](size_t o) { return u8(o) | u8(o + 1) << 8; };
    auto le32 = [&](size_t o) { return le16(o) | le16(o + 2) << 16; };
    TImageHeader r;
    if (n >= 24 && h.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) {
        r.format = "PNG";
        if (h.compare(12, 4, "IHDR") == 0)
            r.width = be32(16), r.height = be32(20);
    } else if (n >= 26 && h[0] == 'B' && h[1] == 'M') {
        r.format = "BMP";
        if (le32(14) == 12) {  // OS/2 header: 16-bit sizes
            r.width = le16(18), r.height = le16(20);
        } else {
            r.width = uint64_t(std::abs(int64_t(int32_t(uint32_t(le32(18))))));
            r.height = uint64_t(std::abs(int64_t(int32_t(uint32_t(le32(22))))));
        }
    } else if (n >= 2 && h[0] == 'P' && h[1] >= '1' && h[1] <= '6') {
        // "P5 <w> <h> ...", comments (#...) between the fields
        r.format = "PNM";
        // P1 / P4 (bitmaps) have no maximum value
        const size_t fields = h[1] == '1' || h[1] == '4' ? 2 : 3;
        std::vector<uint64_t> v;
        size_t i = 2;
        while (v.size() < fields && i < n) {
            if (h[i] == '#') {
                while (i < n && h[i] != '\n')
                    i++;
            } else if (std::isdigit(static_cast<unsigned char>(h[i]))) {
                // every digit is the one number's (saturated at 2^40: a
                // longer one is not split into two)
                uint64_t x = 0;
                for (; i < n && std::isdigit(static_cast<unsigned char>(h[i])); i++)
                    x = std::min(x * 10 + uint64_t(h[i] - '0'), uint64_t(1) << 40);
                v.push_back(x);
                continue;
            } else if (!std::isspace(static_cast<unsigned char>(h[i]))) {
                break;
            }
            i++;
        }
        if (v.size() >= 2)
            r.width = v[0], r.height = v[1];
        if (v.size() == 3)
            r.maxval = v[2];
    } else if (n >= 4 && uint8_t(h[0]) == 0xFF && uint8_t(h[1]) == 0xD8 &&
               uint8_t(h[2]) == 0xFF) {
        // JPEG: walk the segments to the first start-of-frame (SOFn)
        r.format = "JPEG";
        uint64_t pos = 2;
        for (int seg = 0; seg < 100000; seg++) {
            unsigned char m[4];
            f.seekg(std::streamoff(pos));
            if (!f.read(reinterpret_cast<char*>(m), 2) || m[0] != 0xFF)
                break;
            if (m[1] == 0xFF) {  // fill byte
                pos++;
                continue;
            }
            if (m[1] == 0x01 || (m[1] >= 0xD0 && m[1] <= 0xD8)) {  // no length
                pos += 2;
                continue;
            }
            if (m[1] == 0xD9 || m[1] == 0xDA)  // end of image, scan: no frame before
                break;
            const unsigned marker = m[1];
            if (!f.read(reinterpret_cast<char*>(m), 2))
                break;
            const uint64_t len = uint64_t(m[0]) << 8 | m[1];
            if (len < 2)
                break;
            // SOF0..SOF15, not DHT (C4), JPG (C8), DAC (CC)
            if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
                marker != 0xCC) {
                unsigned char d[5];  // precision, height, width
                if (!f.read(reinterpret_cast<char*>(d), 5))
                    break;
                r.height = uint64_t(d[1]) << 8 | d[2];
                r.width = uint64_t(d[3]) << 8 | d[4];
                break;
            }
            pos += 2 + len;
        }
    } else if (n >= 8 &&
               (h.compare(0, 4, "II*\0", 4) == 0 || h.compare(0, 4, "MM\0*", 4) == 0)) {
        // TIFF: the first image file directory's ImageWidth / ImageLength
        r.format = "TIFF";
        const bool le = h[0] == 'I';
        auto rd = [&](uint64_t at, int bytes) -> std::optional<uint64_t> {
            unsigned char b[4];
            f.seekg(std::streamoff(at));
            if (!f.read(reinterpret_cast<char*>(b), bytes))
                return std::nullopt;
            uint64_t v = 0;
            for (int k = 0; k < bytes; k++)
                v |= uint64_t(b[k]) << (8 * (le ? k : bytes - 1 - k));
            return v;
        };
        const auto ifd = rd(4, 4);
        const auto count = ifd ? rd(*ifd, 2) : std::nullopt;
        for (uint64_t e = 0; count && e < *count; e++) {
            const uint64_t at = *ifd + 2 + 12 * e;
            const auto tag = rd(at, 2), type = rd(at + 2, 2);
            if (!tag || !type)
                break;
            if (*tag != 256 && *tag != 257)
                continue;
            // SHORT (3) or LONG (4), one value, stored in the entry itself
            const auto v = *type == 3   ? rd(at + 8, 2)
                           : *type == 4 ? rd(at + 8, 4)
                                        : std::nullopt;
            if (!v)
                break;
            (*tag == 256 ? r.width : r.height) = *v;
        }
    }
    return r;
}
}  // namespace

COccupancyGridMap2D fromImage(const std::string& file, double res, double ox, double oy,
                              TPixelModel model, const TRosParams& ros) {
    // before decoding: a small file can hold a huge image (a 439 KB PNG of
    // 20000 x 20000 px took 4.4 GB, a 162-byte JPEG can claim 30000 x 30000)
    const TImageHeader hd = imageHeader(file);
    if (hd.format.empty())
        throw CBadInputError(file +
                             ": cannot read the map image (not a PNG, BMP, PGM/PPM/PBM, "
                             "JPEG or TIFF, the formats whose size is checked before "
                             "decoding)");
    if (hd.width == 0 || hd.height == 0)
        throw CBadInputError(file + ": cannot read the map image (a " + hd.format +
                             " header without its size)");
    if (hd.width * hd.height > kMaxGridCells)
        throw CBadInputError(file + ": the map image is " + std::to_string(hd.width) +
                             " x " + std::to_string(hd.height) + " px, more than " +
                             cellsText(kMaxGridCells) + " (one cell per pixel)");
    cv::Mat img;
    try {
        const CStderrSilenced quiet;  // libpng prints its own lines on a bad file
        img = cv::imread(file, cv::IMREAD_GRAYSCALE);
    } catch (const std::exception&) {
    }
    if (img.empty())
        throw CBadInputError(file + ": cannot read the map image (a corrupt " +
                             hd.format + ")");
    if (img.cols < 2 || img.rows < 2)
        throw CBadInputError(file + ": map image is too small (" +
                             std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                             " px)");
    const float x0 = float(ox), x1 = float(ox + img.cols * res), y0 = float(oy),
                y1 = float(oy + img.rows * res);
    if (const auto [nx, ny] = setSizeCells(x0, x1, y0, y1, float(res));
        nx * ny > kMaxGridCells || nx == 0)
        throw CBadInputError(file + ": the map image gives a grid of " +
                             std::to_string(nx) + " x " + std::to_string(ny) + " cells");
    COccupancyGridMap2D g;
    // Cell centres: the grid spans exactly the image (cols*res by rows*res).
    g.setSize(x0, x1, y0, y1, static_cast<float>(res), 0.5f);
    const int nx = static_cast<int>(g.getSizeX()), ny = static_cast<int>(g.getSizeY());
    // a PGM's white is its header's maximum value; OpenCV keeps an 8-bit
    // one's samples as they are (a map saved with maximum 100 read as grey)
    const double white = hd.format == "PNM" && hd.maxval > 0 && hd.maxval < 255
                             ? double(hd.maxval)
                             : 255.0;
    for (int cy = 0; cy < ny; cy++) {
        const int row = img.rows - 1 - std::min(cy, img.rows - 1);  // image row 0 = top
        const uint8_t* p = img.ptr<uint8_t>(row);
        for (int cx = 0; cx < nx; cx++) {
            const double grey = std::min(1.0, p[std::min(cx, img.cols - 1)] / white);
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

namespace {
/** One value of a ROS map YAML: a scalar or a list of scalars. */
struct TYamlValue {
    std::string scalar;
    std::vector<std::string> list;
    bool isList = false;
    size_t line = 0;
};

/** Parses a map_server YAML with libyaml: a mapping of keys to scalars or
 * lists of scalars. libyaml rather than MRPT's yaml or yaml-cpp: its event
 * stream shows every key, so a key given twice is seen (the others keep the
 * last or the first silently), and it parses without recursion (yaml-cpp
 * 0.7 overflows its stack on deeply nested input). Values of keys risknav
 * does not know may be anything and are skipped. */
std::map<std::string, TYamlValue> parseMapYaml(const std::string& file) {
    std::string text;
    {
        std::ifstream f(file, std::ios::binary);
        if (!f.good())
            throw CBadInputError(file + ": cannot read the map YAML");
        const size_t cap = 1 << 20;
        text.resize(cap + 1);
        f.read(&text[0], std::streamsize(text.size()));
        text.resize(size_t(f.gcount()));
        if (text.size() > cap)
            throw CBadInputError(file + ": larger than 1 MiB, not a map YAML");
    }
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser))
        throw std::bad_alloc();
    yaml_parser_set_input_string(
        &parser, reinterpret_cast<const unsigned char*>(text.data()), text.size());
    struct TGuard {
        yaml_parser_t* p;
        ~TGuard() { yaml_parser_delete(p); }
    } guard{&parser};
    yaml_event_t ev;
    auto bad = [&](size_t line, const std::string& why) {
        return CBadInputError(file + ":" + std::to_string(line) + ": " + why);
    };
    // The next event; the caller owns it until the next call.
    bool have = false;
    auto next = [&]() -> yaml_event_t& {
        if (have)
            yaml_event_delete(&ev);
        have = false;
        if (!yaml_parser_parse(&parser, &ev))
            throw bad(parser.problem_mark.line + 1,
                      std::string("not YAML: ") +
                          (parser.problem ? parser.problem : "parse error"));
        have = true;
        return ev;
    };
    struct TEventGuard {
        bool& have;
        yaml_event_t& ev;
        ~TEventGuard() {
            if (have)
                yaml_event_delete(&ev);
        }
    } evGuard{have, ev};
    auto line = [](const yaml_event_t& e) { return size_t(e.start_mark.line) + 1; };
    // ("\0" in a quoted scalar is a NUL, which a file name would end at)
    auto scalar = [&](const yaml_event_t& e) {
        std::string s(reinterpret_cast<const char*>(e.data.scalar.value),
                      e.data.scalar.length);
        if (s.find('\0') != std::string::npos)
            throw bad(line(e), "a value with a NUL character");
        return s;
    };
    std::map<std::string, TYamlValue> kv;
    if (next().type != YAML_STREAM_START_EVENT ||
        next().type != YAML_DOCUMENT_START_EVENT)
        throw bad(1, "empty, not a map YAML");
    if (next().type != YAML_MAPPING_START_EVENT)
        throw bad(line(ev), "not a mapping of keys (image: ..., resolution: ...)");
    for (;;) {
        if (next().type == YAML_MAPPING_END_EVENT)
            break;
        if (ev.type == YAML_ALIAS_EVENT)
            throw bad(line(ev), "an alias (*name) as a key");
        if (ev.type != YAML_SCALAR_EVENT)
            throw bad(line(ev), "a key that is not a plain name");
        const std::string key = scalar(ev);
        TYamlValue v;
        v.line = line(ev);
        if (const auto it = kv.find(key); it != kv.end())
            throw bad(v.line, "key '" + clippedText(key) +
                                  "' given twice (also on line " +
                                  std::to_string(it->second.line) + ")");
        next();
        if (ev.type == YAML_ALIAS_EVENT)
            throw bad(line(ev), "key '" + key + "': an alias (*name) as its value");
        if (ev.type == YAML_SCALAR_EVENT) {
            v.scalar = scalar(ev);
        } else {
            // a list or a mapping: kept as a list when it is a flat list of
            // scalars, skipped otherwise (and refused below for a known key)
            const bool isSeq = ev.type == YAML_SEQUENCE_START_EVENT;
            v.isList = isSeq;
            for (int depth = 1; depth > 0;) {
                next();
                if (ev.type == YAML_SEQUENCE_START_EVENT ||
                    ev.type == YAML_MAPPING_START_EVENT) {
                    depth++;
                    v.isList = false;
                } else if (ev.type == YAML_SEQUENCE_END_EVENT ||
                           ev.type == YAML_MAPPING_END_EVENT) {
                    depth--;
                } else if (ev.type == YAML_SCALAR_EVENT && depth == 1 && isSeq) {
                    v.list.push_back(scalar(ev));
                } else if (ev.type != YAML_SCALAR_EVENT) {
                    v.isList = false;  // an alias
                }
                if (depth > 64)
                    throw bad(line(ev), "key '" + key + "': nested too deeply");
            }
            if (!v.isList)
                v.list.clear(), v.scalar = "\x01";  // marks "not a scalar"
        }
        kv.emplace(key, std::move(v));
    }
    if (next().type != YAML_DOCUMENT_END_EVENT)
        throw bad(line(ev), "more than one mapping");
    if (next().type != YAML_STREAM_END_EVENT)
        throw bad(line(ev), "more than one YAML document");
    return kv;
}
}  // namespace

// ROS map_server's YAML (image, resolution, origin, negate, occupied_thresh,
// free_thresh, mode), parsed as YAML; each value is checked.
COccupancyGridMap2D fromRosYaml(const std::string& file) {
    const auto kv = parseMapYaml(file);
    auto where = [&](const std::string& k) {
        return file + ":" + std::to_string(kv.at(k).line) + ": " + k;
    };
    auto has = [&](const std::string& k) { return kv.count(k) > 0; };
    // a scalar value (not a list, not null)
    auto text = [&](const std::string& k) {
        const TYamlValue& v = kv.at(k);
        if (v.isList || v.scalar == "\x01")
            throw CBadInputError(where(k) + " must be a single value, not a list");
        if (v.scalar.empty() || v.scalar == "~" || v.scalar == "null")
            throw CBadInputError(where(k) + " has no value");
        return v.scalar;
    };
    auto need = [&](const std::string& k) {
        if (!has(k))
            throw CBadInputError(file + ": map YAML has no '" + k + "' key");
        return text(k);
    };
    // the one number rule of risknav's readers: decimal, finite
    auto toNumber = [](const std::string& v, double& d) { return parseNumber(v, d); };
    auto number = [&](const std::string& k) {
        const std::string v = text(k);
        double d = 0;
        if (!toNumber(v, d))
            throw CBadInputError(where(k) + " = '" + clippedText(v) +
                                 "' is not a number");
        return d;
    };
    fs::path img = need("image");
    if (img.is_relative())
        img = fs::path(file).parent_path() / img;
    need("resolution");
    const double res = number("resolution");
    if (!(res >= 0.001 && res <= 10))
        throw CBadInputError(where("resolution") + " = '" + text("resolution") +
                             "' must be in [0.001, 10] m");
    if (!has("origin"))
        throw CBadInputError(file + ": map YAML has no 'origin' key");
    const TYamlValue& o = kv.at("origin");
    if (!o.isList || o.list.size() != 3)
        throw CBadInputError(where("origin") + " must be a list [x, y, yaw]");
    double org[3];
    for (int i = 0; i < 3; i++)
        if (!toNumber(o.list[size_t(i)], org[i]))
            throw CBadInputError(where("origin") + ": '" +
                                 clippedText(o.list[size_t(i)]) + "' is not a number");
    const double ox = org[0], oy = org[1], oyaw = org[2];
    if (!(std::abs(ox) <= 1e6 && std::abs(oy) <= 1e6))
        throw CBadInputError(where("origin") + ": x, y must be in [-1e6, 1e6] m");
    if (oyaw != 0.0)
        throw CBadInputError(where("origin") + ": yaw != 0 is not supported");
    TRosParams rp;
    for (const auto& [k, dst] :
         {std::pair<const char*, double*>{"occupied_thresh", &rp.occupied},
          std::pair<const char*, double*>{"free_thresh", &rp.free}}) {
        if (!has(k))
            continue;
        const std::string v = text(k);
        double d = 0;
        // map_server's thresholds are probabilities in [0, 1], free below
        // occupied; anything else (nan, inf, 2) would silently turn every
        // wall into unknown.
        if (!toNumber(v, d) || !(d >= 0 && d <= 1))
            throw CBadInputError(where(k) + " = '" + clippedText(v) +
                                 "' must be in [0, 1]");
        *dst = d;
    }
    if (!(rp.free < rp.occupied))
        throw CBadInputError(file + ": map YAML free_thresh must be < occupied_thresh");
    if (has("negate")) {
        const std::string n = text("negate");
        if (n != "0" && n != "1" && n != "true" && n != "false")
            throw CBadInputError(where("negate") + " = '" + clippedText(n) +
                                 "' must be 0 or 1");
        rp.negate = n == "1" || n == "true";
    }
    const std::string mode = has("mode") ? text("mode") : "trinary";
    if (mode != "trinary" && mode != "scale")
        throw CBadInputError(where("mode") + " = '" + clippedText(mode) +
                             "' is not supported (trinary, scale)");
    if (const std::string why = fileProblem(img.string()); !why.empty())
        throw CBadInputError(file + ": map image " + why + ": " + img.string());
    return fromImage(img.string(), res, ox, oy,
                     mode == "scale" ? TPixelModel::RosScale : TPixelModel::RosTrinary,
                     rp);
}
}  // namespace risknav::common::grid_readers
