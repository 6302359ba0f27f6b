#include <risknav/common/CAllocationBudget.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/common/grid_io.h>
#include <risknav/common/probe_in_child.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "grid_readers.h"

// MRPT's own map files: .gridmap and .simplemap (loadOccupancyGrid(),
// grid_io.cpp).
namespace fs = std::filesystem;
using mrpt::maps::COccupancyGridMap2D;

namespace risknav::common::grid_readers {
namespace {
/** The bytes of a plain or gz-compressed file, no more than `cap` (more:
 * CBadInputError with `tooLarge`). */
std::string readAtMost(const std::string& file, size_t cap, const std::string& tooLarge,
                       const std::string& unreadable) {
    std::string bytes;
    try {
        mrpt::io::CFileGZInputStream f(file);
        std::vector<char> buf(1 << 16);
        for (;;) {
            const size_t n = f.Read(buf.data(), buf.size());
            // MRPT passes gzread's -1 (a corrupt stream) on as a huge size_t
            if (n > buf.size())
                throw CBadInputError(unreadable + " (a corrupt gzip stream)");
            if (n == 0)
                break;
            bytes.append(buf.data(), n);
            if (bytes.size() > cap)
                throw CBadInputError(tooLarge);
        }
    } catch (const CBadInputError&) {
        throw;
    } catch (const std::exception&) {
        throw CBadInputError(unreadable);
    }
    return bytes;
}
}  // namespace

// A .gridmap is MRPT's serialized COccupancyGridMap2D. Its header (class
// name, version, bits per cell, size_x, size_y, bounds, resolution) is
// checked BEFORE any grid is allocated: a corrupt header (zeroed, resolution
// 0, huge sizes, bounds far beyond the size) made MRPT allocate gigabytes.
// Every serialization version MRPT 2.5 reads (0..6; 8- or 16-bit cells,
// the pre-0.5.5 object header) is read; the file is decompressed no further
// than the largest grid needs.
COccupancyGridMap2D fromGridmap(const std::string& file) {
    const std::string unreadable = file + ": not a readable MRPT .gridmap file";
    const std::string bytes =
        readAtMost(file, size_t(2 * kMaxGridCells) + (1u << 20),
                   file + ": larger than the largest map risknav reads (" +
                       cellsText(kMaxGridCells) + ")",
                   unreadable);
    auto bad = [&](const std::string& why) {
        return CBadInputError(unreadable + " (" + why + ")");
    };
    auto u8 = [&](size_t at) { return at < bytes.size() ? uint8_t(bytes[at]) : 0; };
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        for (int k = 3; k >= 0; k--)
            v = (v << 8) | u8(at + size_t(k));
        return v;
    };
    auto f32 = [&](size_t at) {
        const uint32_t u = u32(at);
        float v;
        std::memcpy(&v, &u, 4);
        return v;
    };
    // The object header (CArchive): 0x80 | name length, name, version byte;
    // or (before MRPT 0.5.5) a 32-bit name length, name, 32-bit version.
    const bool oldHeader = !(u8(0) & 0x80);
    const size_t nameLen = oldHeader ? u32(0) : size_t(u8(0) & 0x7F);
    const size_t nameAt = oldHeader ? 4 : 1;
    const std::string cls = "COccupancyGridMap2D";
    if (bytes.size() < nameAt + nameLen + 4 || nameLen > 120 || nameLen < cls.size())
        throw bad("no COccupancyGridMap2D header");
    // MRPT also finds a class by its name without namespace (old datasets)
    const std::string name = bytes.substr(nameAt, nameLen);
    if (name.compare(nameLen - cls.size(), cls.size(), cls) != 0 ||
        !(nameLen == cls.size() || name.compare(nameLen - cls.size() - 2, 2, "::") == 0))
        throw bad("no COccupancyGridMap2D header");
    size_t o = nameAt + nameLen;
    const uint32_t version = oldHeader ? u32(o) : u8(o);
    o += oldHeader ? 4 : 1;
    if (version > 6)
        throw bad("serialization version " + std::to_string(version) +
                  "; MRPT 2.5 reads 0 to 6");
    const unsigned bits = version >= 2 ? u8(o++) : 8;
    if (bits != 8 && bits != 16)
        throw bad("cells of " + std::to_string(bits) + " bits");
    if (bytes.size() < o + 28)
        throw bad("truncated header");
    const uint64_t sx = u32(o), sy = u32(o + 4);
    const float x0 = f32(o + 8), x1 = f32(o + 12), y0 = f32(o + 16), y1 = f32(o + 20),
                res = f32(o + 24);
    o += 28;
    if (!(res >= 0.001f && res <= 10))
        throw bad("resolution " + std::to_string(res) + " m");
    if (!(std::abs(x0) <= 1e6f && std::abs(x1) <= 1e6f && std::abs(y0) <= 1e6f &&
          std::abs(y1) <= 1e6f && x0 < x1 && y0 < y1))
        throw bad("map bounds");
    if (sx == 0 || sy == 0 || sx * sy > kMaxGridCells)
        throw bad(std::to_string(sx) + " x " + std::to_string(sy) + " cells");
    // MRPT sizes the grid from the bounds, not from size_x / size_y: both
    // must agree (1 x 1 cells over 2 km at 1 mm would be 4e12 cells).
    if (const auto [nx, ny] = setSizeCells(x0, x1, y0, y1, res); nx != sx || ny != sy)
        throw bad("size " + std::to_string(sx) + " x " + std::to_string(sy) +
                  " cells does not match its bounds and resolution (" +
                  std::to_string(nx) + " x " + std::to_string(ny) + ")");
    const uint64_t cellBytes = bits / 8;
    if (sx * sy * cellBytes > bytes.size() - o)
        throw bad("truncated: " + std::to_string(sx) + " x " + std::to_string(sy) +
                  " cells announced");
    // The grid is built from the checked header and its cells; the options
    // MRPT stores after the cells (insertion / likelihood settings, which
    // risknav sets itself) are not read: their lengths come from the file
    // too, and a corrupt one made MRPT allocate gigabytes.
    COccupancyGridMap2D g;
    g.setSize(x0, x1, y0, y1, res);
    const unsigned char* cells = reinterpret_cast<const unsigned char*>(bytes.data()) + o;
    for (uint64_t cy = 0; cy < sy; cy++) {
        auto* row = g.getRow(int(cy));
        for (uint64_t cx = 0; cx < sx; cx++) {
            const uint64_t i = cy * sx + cx;
            // 16-bit cells: MRPT keeps the high byte (of a little-endian word)
            const uint8_t c = bits == 8 ? cells[i] : cells[2 * i + 1];
            if (version < 3) {
                // before version 3 cells were probabilities (0..255), not
                // log-odds: MRPT converts them as it reads
                row[cx] = COccupancyGridMap2D::p2l(float(double(c) * (1.0f / 0xFF)));
            } else {
                std::memcpy(&row[cx], &c, 1);
            }
        }
    }
    return g;
}

namespace {
// What MRPT may allocate while deserializing a simplemap: as for a rawlog
// entry (CRawlogReader), a base plus a small multiple of the decompressed
// bytes: a real simplemap's arrays are stored in it.
constexpr uint64_t kSimplemapBudgetBase = 64ull << 20;
constexpr uint64_t kSimplemapBudgetPerByte = 16;
// The largest decompressed simplemap read (its budget stays below 16 GiB).
constexpr size_t kMaxSimplemapBytes = size_t(1) << 30;
// MRPT inserts a scan with two stack buffers of its ray count (alloca).
constexpr size_t kMaxScanRays = 100000;

void readSimplemap(const std::string& file, mrpt::maps::CSimpleMap& sm, size_t budget) {
    mrpt::io::CFileGZInputStream f(file);
    auto a = mrpt::serialization::archiveFrom(f);
    const CAllocationBudget b(budget);
    a >> sm;
}
}  // namespace

// A .simplemap is MRPT's CSimpleMap: keyframes (pose PDF, sensory frame).
// MRPT 2.5 segfaults on some corrupt ones (a keyframe pose that is null or of
// another class) and allocates what the file's counts say: the file is read
// first in a forked child (probeInChild), then here under an allocation
// budget. The grid its 2D scans give is sized before it is allocated.
COccupancyGridMap2D fromSimplemap(const std::string& file, double res,
                                  const std::string& section) {
    const std::string unreadable = file + ": not a readable MRPT .simplemap file";
    uint64_t bytes = 0;
    {
        try {
            mrpt::io::CFileGZInputStream f(file);
            std::vector<char> buf(1 << 16);
            for (size_t n; (n = f.Read(buf.data(), buf.size())) > 0;) {
                if (n > buf.size())
                    throw CBadInputError(unreadable + " (a corrupt gzip stream)");
                bytes += n;
                if (bytes > kMaxSimplemapBytes)
                    throw CBadInputError(file +
                                         ": larger than 1 GiB, more than risknav reads");
            }
        } catch (const CBadInputError&) {
            throw;
        } catch (const std::exception&) {
            throw CBadInputError(unreadable);
        }
    }
    const size_t budget = size_t(kSimplemapBudgetBase + kSimplemapBudgetPerByte * bytes);
    if (common::probeInChild([&](const TProbeProgress&) {
            mrpt::maps::CSimpleMap sm;
            readSimplemap(file, sm, budget);
        }))
        throw CBadInputError(unreadable +
                             " (MRPT's deserializer crashes on it: a null or mistyped "
                             "object inside)");
    mrpt::maps::CSimpleMap sm;
    bool overBudget = false;
    try {
        readSimplemap(file, sm, budget);
    } catch (const std::bad_alloc&) {
        overBudget = true;
    } catch (const std::exception&) {
        throw CBadInputError(unreadable);
    }
    if (overBudget)
        throw CBadInputError(unreadable + " (its counts ask for more than " +
                             std::to_string(budget >> 20) + " MiB)");
    if (sm.empty())
        throw CBadInputError(file + ": the simplemap has no keyframes");
    // The extent of the grid: every 2D scan's rays as MRPT inserts them (no
    // longer than maxDistanceInsertion, invalid ones half the last valid).
    COccupancyGridMap2D g;
    const float maxIns = g.insertionOptions.maxDistanceInsertion;
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    struct TScan {
        mrpt::poses::CPose3D robot;
        const mrpt::obs::CObservation2DRangeScan* scan;
    };
    std::vector<TScan> scans;
    for (size_t i = 0; i < sm.size(); i++) {
        const auto [pdf, sf] = sm.get(i);
        const std::string at = file + ": keyframe " + std::to_string(i);
        if (!pdf || !sf)
            throw CBadInputError(at + " has no pose or no observations");
        mrpt::poses::CPose3D robot;
        pdf->getMean(robot);
        auto sane = [](const mrpt::poses::CPose3D& p) {
            for (const double v : {p.x(), p.y(), p.z(), p.yaw(), p.pitch(), p.roll()})
                if (!(std::abs(v) <= 1e6))
                    return false;
            return true;
        };
        if (!sane(robot))
            throw CBadInputError(at + ": its pose is not finite or beyond 1e6 m");
        for (const auto& obs : *sf) {
            if (!obs)
                throw CBadInputError(at + ": a null observation");
            const auto* scan =
                dynamic_cast<const mrpt::obs::CObservation2DRangeScan*>(obs.get());
            if (!scan)
                continue;  // the grid takes 2D scans only
            if (!sane(scan->sensorPose) || !std::isfinite(scan->aperture))
                throw CBadInputError(at +
                                     ": a scan's sensor pose or aperture is not finite");
            const size_t n = scan->getScanSize();
            if (n > kMaxScanRays)
                throw CBadInputError(at + ": a scan of " + std::to_string(n) +
                                     " rays, more than " + std::to_string(kMaxScanRays));
            float longest = 0.5f * maxIns;
            for (size_t k = 0; k < n; k++) {
                if (!scan->getScanRangeValidity(k))
                    continue;
                const float r = scan->getScanRange(k);
                // (MRPT draws a negative range backwards, off the grid)
                if (!(r >= 0 && std::isfinite(r)))
                    throw CBadInputError(at + ": a scan range is negative or not finite");
                longest = std::max(longest, r);
            }
            const double reach = std::min(maxIns, longest);
            const mrpt::poses::CPose3D sensor = robot + scan->sensorPose;
            xmin = std::min(xmin, sensor.x() - reach);
            xmax = std::max(xmax, sensor.x() + reach);
            ymin = std::min(ymin, sensor.y() - reach);
            ymax = std::max(ymax, sensor.y() + reach);
            scans.push_back({robot, scan});
        }
    }
    if (scans.empty())
        throw CBadInputError(file + ": the simplemap has no 2D laser scans");
    // MRPT grows a grid that comes within 15 cells of a scan: a margin of 20
    // keeps it at this size.
    const double margin = 20 * res;
    const float x0 = float(xmin - margin), x1 = float(xmax + margin),
                y0 = float(ymin - margin), y1 = float(ymax + margin);
    const auto [nx, ny] = setSizeCells(x0, x1, y0, y1, float(res));
    if (nx * ny > kMaxGridCells || nx == 0)
        throw CBadInputError(
            file + ": its scans span " + std::to_string(int64_t(std::ceil(x1 - x0))) +
            " x " + std::to_string(int64_t(std::ceil(y1 - y0))) + " m, " +
            std::to_string(nx) + " x " + std::to_string(ny) + " cells at [" + section +
            "] simplemap_resolution = " +
            [&] {
                std::ostringstream t;
                t << res;
                return t.str();
            }() +
            " m, more than " + cellsText(kMaxGridCells) + " (a coarser resolution)");
    g.setSize(x0, x1, y0, y1, float(res), 0.5f);
    try {
        for (const auto& s : scans)
            g.insertObservation(*s.scan, s.robot);
    } catch (const std::exception& e) {
        // MRPT's own checks (a ray off the grid): the file's scans are to blame
        std::string why = e.what();
        const auto m = why.find("Message:");
        why = why.substr(m == std::string::npos ? 0 : m + 8);
        why = trim(why.substr(0, why.find('\n')));
        throw CBadInputError(file + ": MRPT cannot insert its scans into a grid (" +
                             clippedText(why, 160) + ")");
    }
    return g;
}
}  // namespace risknav::common::grid_readers
