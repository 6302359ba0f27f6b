// The .afraid file format: round trip, version 1 files, explicit byte order,
// and refusal of truncated, foreign, newer, corrupt and oversized files.
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/common/CBadInputError.h>

#include <mrpt/io/CFileGZOutputStream.h>

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>

#include "test_support.h"

using namespace risknav::afraid;
using risknav::common::CBadInputError;

namespace {
mrpt::maps::COccupancyGridMap2D smallMap() {
    mrpt::maps::COccupancyGridMap2D g(-1, 9, 0.5, 4.5, 0.05f);
    g.fill(1.0f);
    return g;
}

// A grid with some experience in it (random but seeded).
CAfraidGrid filledGrid() {
    CAfraidGrid g(smallMap());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 2000; i++) {
        const double x = -1 + 10 * u(rng), y = 2 + 0.2 * u(rng);
        g.addExposure(x, y);
        if (u(rng) < 0.05) {
            g.addRobotEvent(x, y);
            g.addObstacleEvent(x + 0.3, y + 1.0);
        }
    }
    g.runs = 3;
    g.frames = 0x0102030405060708ULL;  // every byte different: shows the byte order
    return g;
}

// Little-endian bytes, written out one by one (what any host must produce).
void le(std::string& b, uint64_t v, int n) {
    for (int k = 0; k < n; k++)
        b.push_back(char((v >> (8 * k)) & 0xff));
}
void leF64(std::string& b, double v) {
    uint64_t u;
    std::memcpy(&u, &v, 8);
    le(b, u, 8);
}

// The .afraid content, laid out field by field (version, geometry and layers
// as given); version 1 is the format risknav wrote before version 2, version 2
// has no passes layer.
std::string layout(uint32_t version, const CAfraidGrid& g) {
    std::string b = "RNAFRAID";
    le(b, version, 4);
    leF64(b, g.xMin());
    leF64(b, g.yMin());
    leF64(b, g.resolution());
    le(b, uint32_t(g.sizeX()), 4);
    le(b, uint32_t(g.sizeY()), 4);
    le(b, g.runs, 4);
    le(b, g.frames, 8);
    std::vector<const std::vector<uint32_t>*> layers = {&g.exposure(), &g.robotEvents(),
                                                        &g.obstacleEvents()};
    if (version >= 3)
        layers.push_back(&g.passes());
    for (const auto* layer : layers) {
        uint32_t n = 0;
        for (uint32_t v : *layer)
            n += v != 0;
        le(b, n, 4);
        for (uint32_t i = 0; i < layer->size(); i++)
            if ((*layer)[i]) {
                le(b, i, 4);
                le(b, (*layer)[i], 4);
            }
    }
    return b;
}

void writeGz(const std::string& path, const std::string& bytes) {
    mrpt::io::CFileGZOutputStream f;
    ASSERT_TRUE(f.open(path));
    ASSERT_EQ(f.Write(bytes.data(), bytes.size()), bytes.size());
    f.close();
}

void expectSameGrid(const CAfraidGrid& a, const CAfraidGrid& b) {
    EXPECT_TRUE(a.sameGeometry(b));
    EXPECT_EQ(a.sizeX(), b.sizeX());
    EXPECT_EQ(a.sizeY(), b.sizeY());
    EXPECT_EQ(a.xMin(), b.xMin());
    EXPECT_EQ(a.yMin(), b.yMin());
    EXPECT_EQ(a.resolution(), b.resolution());
    EXPECT_EQ(a.exposure(), b.exposure());
    EXPECT_EQ(a.robotEvents(), b.robotEvents());
    EXPECT_EQ(a.obstacleEvents(), b.obstacleEvents());
    EXPECT_EQ(a.runs, b.runs);
    EXPECT_EQ(a.frames, b.frames);
}

// f must throw a one-line CBadInputError that names `file` and says `what`.
void expectRefused(const std::function<void()>& f, const std::string& file,
                   const std::string& what) {
    try {
        f();
        ADD_FAILURE() << file << ": accepted, expected '" << what << "'";
    } catch (const CBadInputError& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind(file + ": ", 0), 0u) << m;
        EXPECT_NE(m.find(what), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    } catch (const std::exception& e) {
        ADD_FAILURE() << file << ": not a CBadInputError: " << e.what();
    }
}
}  // namespace

TEST(AfraidFile, RoundTrip) {
    const CAfraidGrid g = filledGrid();
    ASSERT_GT(g.totalRobotEvents(), 50u);
    const std::string d = risknav::test::freshDir("afraid-file");
    g.save(d + "/g.afraid");
    const CAfraidGrid h = CAfraidGrid::load(d + "/g.afraid");
    expectSameGrid(h, g);
    EXPECT_EQ(h.encode(), g.encode());
    // An empty grid too.
    const CAfraidGrid e(smallMap());
    e.save(d + "/e.afraid");
    expectSameGrid(CAfraidGrid::load(d + "/e.afraid"), e);
}

TEST(AfraidFile, Version3IsLittleEndianByteByByte) {
    // encode() equals the layout written out byte by byte, whatever the host.
    CAfraidGrid g = filledGrid();
    g.addTraversal(-0.9, 0.1, 0.9, 0.1);
    EXPECT_EQ(CAfraidGrid::kVersion, 3u);
    EXPECT_EQ(g.encode(), layout(3, g));
    const std::string b = g.encode();
    EXPECT_EQ(b.substr(8, 4), std::string("\x03\x00\x00\x00", 4));
    EXPECT_EQ(b.substr(36, 4), std::string("\xc8\x00\x00\x00", 4));  // 200 columns
    EXPECT_EQ(b.substr(48, 8), std::string("\x08\x07\x06\x05\x04\x03\x02\x01", 8));
}

TEST(AfraidFile, Versions1And2StillLoad) {
    // Files of the versions before (v1: before the explicit byte order, as
    // risknav wrote it on little-endian hosts; v2: no passes layer) load to the
    // same grid, their frames taken as passes; saving again writes version 3.
    const CAfraidGrid g = filledGrid();
    const std::string d = risknav::test::freshDir("afraid-file");
    for (uint32_t v : {1u, 2u}) {
        const std::string f = d + "/v" + std::to_string(v) + ".afraid";
        writeGz(f, layout(v, g));
        const CAfraidGrid h = CAfraidGrid::load(f);
        expectSameGrid(h, g);
        EXPECT_EQ(h.passes(), g.exposure()) << v;
        EXPECT_EQ(h.encode(), layout(3, h));
    }
    // Version 1's leniency: trailing bytes were ignored and still are.
    writeGz(d + "/v1tail.afraid", layout(1, g) + "tail");
    expectSameGrid(CAfraidGrid::load(d + "/v1tail.afraid"), g);
    // Resuming from a version 1 file: merging gives the sum.
    CAfraidGrid m = filledGrid();
    m.merge(CAfraidGrid::load(d + "/v1.afraid"));
    EXPECT_EQ(m.totalRobotEvents(), 2 * g.totalRobotEvents());
}

TEST(AfraidFile, TruncatedIsRefused) {
    const CAfraidGrid g = filledGrid();
    const std::string b = g.encode();
    // Every cut of the content: refused, never a smaller grid.
    for (size_t k = 0; k < b.size(); k++)
        expectRefused([&] { CAfraidGrid::decode(b.substr(0, k), "cut.afraid"); },
                      "cut.afraid", k < 8 ? "not a risknav .afraid file" : "truncated");
    // A gz file cut in half.
    const std::string d = risknav::test::freshDir("afraid-file");
    g.save(d + "/ok.afraid");
    const std::string full = risknav::test::readFile(d + "/ok.afraid");
    risknav::test::writeFile(d + "/cut.afraid", full.substr(0, full.size() / 2));
    expectRefused([&] { CAfraidGrid::load(d + "/cut.afraid"); }, d + "/cut.afraid", "");
    // Content cut after the header and the first layer, compressed whole.
    writeGz(d + "/short.afraid", b.substr(0, 56 + 4 + 8 * 10));
    expectRefused([&] { CAfraidGrid::load(d + "/short.afraid"); }, d + "/short.afraid",
                  "truncated .afraid file");
}

TEST(AfraidFile, BytesAfterTheGzStreamOrABadCrcAreRefused) {
    // zlib reads a gzip stream to its end and ignores what follows; a bad
    // CRC came out of MRPT's reader as a huge count ("basic_string::append")
    const CAfraidGrid g = filledGrid();
    const std::string d = risknav::test::freshDir("afraid-tail");
    g.save(d + "/ok.afraid");
    const std::string full = risknav::test::readFile(d + "/ok.afraid");
    EXPECT_NO_THROW(CAfraidGrid::load(d + "/ok.afraid"));
    risknav::test::writeFile(d + "/tail.afraid", full + std::string(5000, 'x'));
    expectRefused([&] { CAfraidGrid::load(d + "/tail.afraid"); }, d + "/tail.afraid",
                  "corrupt .afraid file (bytes after its gz stream)");
    std::string crc = full;
    crc[crc.size() - 6] = char(crc[crc.size() - 6] ^ 0x5a);  // in the CRC32 field
    risknav::test::writeFile(d + "/crc.afraid", crc);
    expectRefused([&] { CAfraidGrid::load(d + "/crc.afraid"); }, d + "/crc.afraid",
                  "corrupt .afraid file (gz stream)");
}

TEST(AfraidFile, ForeignNewerAndCorruptAreRefused) {
    const std::string d = risknav::test::freshDir("afraid-file");
    risknav::test::writeFile(d + "/text.afraid", "not an afraid file");
    expectRefused([&] { CAfraidGrid::load(d + "/text.afraid"); }, d + "/text.afraid",
                  "not a risknav .afraid file");
    writeGz(d + "/gz.afraid", std::string(1000, 'x'));
    expectRefused([&] { CAfraidGrid::load(d + "/gz.afraid"); }, d + "/gz.afraid",
                  "not a risknav .afraid file");
    risknav::test::writeFile(d + "/empty.afraid", "");
    expectRefused([&] { CAfraidGrid::load(d + "/empty.afraid"); }, d + "/empty.afraid",
                  "not a risknav .afraid file");
    expectRefused([&] { CAfraidGrid::load(d + "/missing.afraid"); },
                  d + "/missing.afraid", "not found");

    const CAfraidGrid g = filledGrid();
    writeGz(d + "/v4.afraid", layout(4, g));
    expectRefused([&] { CAfraidGrid::load(d + "/v4.afraid"); }, d + "/v4.afraid",
                  ".afraid file version 4 (this build reads 1 to 3)");
    writeGz(d + "/v0.afraid", layout(0, g));
    expectRefused([&] { CAfraidGrid::load(d + "/v0.afraid"); }, d + "/v0.afraid",
                  "version 0");
    // Version 2: nothing after the data, cell indices in order.
    writeGz(d + "/tail.afraid", g.encode() + "x");
    expectRefused([&] { CAfraidGrid::load(d + "/tail.afraid"); }, d + "/tail.afraid",
                  "1 bytes after the data");
    std::string swapped = g.encode();
    std::swap_ranges(swapped.begin() + 60, swapped.begin() + 68, swapped.begin() + 68);
    writeGz(d + "/order.afraid", swapped);
    expectRefused([&] { CAfraidGrid::load(d + "/order.afraid"); }, d + "/order.afraid",
                  "corrupt .afraid file (cell order)");
    // A cell index beyond the grid.
    std::string index = g.encode();
    index[60 + 3] = '\x7f';
    writeGz(d + "/index.afraid", index);
    expectRefused([&] { CAfraidGrid::load(d + "/index.afraid"); }, d + "/index.afraid",
                  "corrupt .afraid file (cell index)");
}

TEST(AfraidFile, OversizedHeadersAreRefusedBeforeAllocating) {
    const std::string d = risknav::test::freshDir("afraid-file");
    auto header = [](int32_t sx, int32_t sy) {
        std::string b = "RNAFRAID";
        le(b, 2, 4);
        leF64(b, 0.0);
        leF64(b, 0.0);
        leF64(b, 0.05);
        le(b, uint32_t(sx), 4);
        le(b, uint32_t(sy), 4);
        le(b, 1, 4);
        le(b, 100, 8);
        return b;
    };
    // 40000 x 40000 cells (19 GB of layers): refused from the header alone.
    writeGz(d + "/huge.afraid", header(40000, 40000) + std::string(12, '\0'));
    expectRefused([&] { CAfraidGrid::load(d + "/huge.afraid"); }, d + "/huge.afraid",
                  "map of 40000 x 40000 cells, more than an afraid grid holds");
    // Sizes that overflow 32 bits, negative, zero.
    for (auto [sx, sy] :
         {std::pair{100000, 100000}, std::pair{-5, 10}, std::pair{0, 7}}) {
        writeGz(d + "/bad.afraid", header(sx, sy) + std::string(12, '\0'));
        expectRefused([&] { CAfraidGrid::load(d + "/bad.afraid"); }, d + "/bad.afraid",
                      "");
    }
    // Within the maximum grid, but a layer announcing more cells than the
    // file's remaining bytes can hold.
    std::string b = header(4000, 4000);
    le(b, 16'000'000, 4);
    b += std::string(64, '\0');
    writeGz(d + "/claims.afraid", b);
    expectRefused([&] { CAfraidGrid::load(d + "/claims.afraid"); }, d + "/claims.afraid",
                  "truncated .afraid file (16000000 cells announced, 64 bytes left)");
    // A layer count above the grid's cells.
    std::string c = header(10, 10);
    le(c, 101, 4);
    writeGz(d + "/count.afraid", c);
    expectRefused([&] { CAfraidGrid::load(d + "/count.afraid"); }, d + "/count.afraid",
                  "corrupt .afraid file (cell count 101 > 100 cells)");
    // A gz bomb: a tiny grid followed by megabytes of zeros is not inflated
    // past what its header allows.
    writeGz(d + "/bomb.afraid", header(10, 10) + std::string(8 << 20, '\0'));
    expectRefused([&] { CAfraidGrid::load(d + "/bomb.afraid"); }, d + "/bomb.afraid",
                  "longer than its header allows");
}

TEST(AfraidFile, MapLargerThanTheMaximumIsRefused) {
    // 6000 x 6000 cells > kMaxCells (the map itself is one byte per cell).
    mrpt::maps::COccupancyGridMap2D big(0, 300, 0, 300, 0.05f);
    EXPECT_THROW(CAfraidGrid{big}, CBadInputError);
}
