#include <risknav/common/CBadInputError.h>
#include <risknav/common/grid_io.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

using namespace risknav::common;
using namespace risknav::test;

namespace {
// 40 x 20 px, white, with a black 4 x 2 px block in the top-left corner.
std::string makePng(const std::string& dir) {
    cv::Mat img(20, 40, CV_8UC1, cv::Scalar(255));
    img(cv::Rect(0, 0, 4, 2)).setTo(0);
    img(cv::Rect(10, 10, 2, 2)).setTo(128);
    const std::string f = dir + "/m.png";
    cv::imwrite(f, img);
    return f;
}
}  // namespace

TEST(GridIO, PngOrientationResolutionOrigin) {
    TMapSourceOptions s;
    s.map_file = makePng(freshDir("m"));
    s.map_resolution = 0.1;
    s.map_origin_x = -1.0;
    s.map_origin_y = 2.0;
    const auto g = loadOccupancyGrid(s);
    EXPECT_EQ(g.getSizeX(), 40u);
    EXPECT_EQ(g.getSizeY(), 20u);
    EXPECT_NEAR(g.getXMin(), -1.0, 1e-6);
    EXPECT_NEAR(g.getYMin(), 2.0, 1e-6);
    EXPECT_NEAR(g.getXMax(), 3.0, 1e-5);
    EXPECT_NEAR(g.getYMax(), 4.0, 1e-5);
    // Image row 0 is the top (max y): the black block is at the top-left.
    EXPECT_LT(g.getPos(-0.95, 3.95), 0.05f);
    EXPECT_GT(g.getPos(-0.95, 2.05), 0.95f);
    EXPECT_NEAR(g.getPos(0.05, 2.85), 128 / 255.0, 0.02);  // grey = uncertain
}

TEST(GridIO, RosYamlTrinary) {
    const std::string d = freshDir("m");
    makePng(d);
    writeFile(d + "/m.yaml",
              "image: m.png\nresolution: 0.05\norigin: [1.0, 2.0, 0.0]\nnegate: 0\n"
              "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
    TMapSourceOptions s;
    s.map_file = d + "/m.yaml";
    const auto g = loadOccupancyGrid(s);
    EXPECT_NEAR(g.getResolution(), 0.05, 1e-6);
    EXPECT_NEAR(g.getXMin(), 1.0, 1e-6);
    EXPECT_LT(g.getCell(0, 19), 0.05f);                    // occupied
    EXPECT_GT(g.getCell(20, 5), 0.95f);                    // free
    EXPECT_NEAR(g.getCell(10, 20 - 1 - 10), 0.5f, 0.02f);  // grey -> unknown

    // MRPT's own ROS loader reads the same file to the same cells.
    mrpt::maps::COccupancyGridMap2D ref;
    ASSERT_TRUE(ref.loadFromROSMapServerYAML(d + "/m.yaml"));
    ASSERT_EQ(ref.getSizeX(), g.getSizeX());
    ASSERT_EQ(ref.getSizeY(), g.getSizeY());
    int differ = 0;
    for (unsigned y = 0; y < g.getSizeY(); y++)
        for (unsigned x = 0; x < g.getSizeX(); x++)
            differ += std::abs(ref.getCell(x, y) - g.getCell(x, y)) > 0.1f;
    EXPECT_EQ(differ, 0);
}

TEST(GridIO, GridmapRoundTrip) {
    const std::string d = freshDir("m");
    TMapSourceOptions s;
    s.map_file = makePng(d);
    const auto g = loadOccupancyGrid(s);
    saveGridmapGz(g, d + "/m.gridmap.gz");
    TMapSourceOptions s2;
    s2.map_file = d + "/m.gridmap.gz";
    const auto h = loadOccupancyGrid(s2);
    ASSERT_EQ(h.getSizeX(), g.getSizeX());
    for (unsigned y = 0; y < g.getSizeY(); y++)
        for (unsigned x = 0; x < g.getSizeX(); x++)
            ASSERT_FLOAT_EQ(h.getCell(x, y), g.getCell(x, y));
}

TEST(GridIO, BadFilesAreBadInput) {
    const std::string d = freshDir("m");
    TMapSourceOptions s;
    s.map_file = d + "/none.png";
    EXPECT_THROW(loadOccupancyGrid(s), CBadInputError);
    writeFile(d + "/text.png", "this is not a png");
    s.map_file = d + "/text.png";
    try {
        loadOccupancyGrid(s);
        FAIL();
    } catch (const CBadInputError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot read the map image"),
                  std::string::npos);
    }
    writeFile(d + "/bad.gridmap.gz", "garbage");
    s.map_file = d + "/bad.gridmap.gz";
    EXPECT_THROW(loadOccupancyGrid(s), CBadInputError);
    writeFile(d + "/m.yaml", "resolution: 0.05\n");
    s.map_file = d + "/m.yaml";
    EXPECT_THROW(loadOccupancyGrid(s), CBadInputError);
}

TEST(GridIO, AnImageOfMoreThan25MPixelsIsRefusedBeforeDecoding) {
    // a header that says 20000 x 20000 (a 439 KB PNG of that size
    // took 4.4 GB): refused from the header, whatever follows
    const std::string d = freshDir("big");
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string("\0\0\0\x0dIHDR", 8);
    png += std::string("\0\0\x4e\x20\0\0\x4e\x20", 8);  // 20000, 20000
    png += std::string("\x08\0\0\0\0\0\0\0\0", 9);
    writeFile(d + "/big.png", png);
    writeFile(d + "/big.pgm", "P5\n# a comment\n6000 5000\n255\n");
    writeFile(d + "/ok.pgm", "P5\n4 3\n255\n" + std::string(12, '\xff'));
    TMapSourceOptions s;
    for (const auto& [f, size] : std::vector<std::pair<std::string, std::string>>{
             {"big.png", "20000 x 20000 px"}, {"big.pgm", "6000 x 5000 px"}}) {
        s.map_file = d + "/" + f;
        try {
            loadOccupancyGrid(s);
            FAIL() << f;
        } catch (const CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find(size + ", more than 25 M cells"),
                      std::string::npos)
                << e.what();
        }
    }
    s.map_file = d + "/ok.pgm";
    EXPECT_EQ(loadOccupancyGrid(s).getSizeX(), 4u);
}

// MRPT's own sample map (package mrpt-common): a grid built from its keyframes.
TEST(GridIO, MrptSimplemapDataset) {
    TMapSourceOptions s;
    s.map_file = "/usr/share/mrpt/datasets/localization_demo.simplemap.gz";
    s.simplemap_resolution = 0.1;
    const auto g = loadOccupancyGrid(s);
    EXPECT_NEAR(g.getResolution(), 0.1, 1e-6);
    EXPECT_GT(g.getXMax() - g.getXMin(), 40.0);  // the demo building spans ~ 70 x 30 m
    EXPECT_GT(g.getYMax() - g.getYMin(), 20.0);
    size_t occupied = 0, freeCells = 0;
    for (unsigned y = 0; y < g.getSizeY(); y++)
        for (unsigned x = 0; x < g.getSizeX(); x++) {
            occupied += g.getCell(x, y) < 0.3f;
            freeCells += g.getCell(x, y) > 0.7f;
        }
    EXPECT_GT(occupied, 1000u);
    EXPECT_GT(freeCells, 10000u);
}

// map_server YAML values that would silently change the map (every wall
// unknown, no obstacle) or break MRPT's grid arithmetic: refused, one line.
TEST(GridIO, RosYamlValuesOutOfRangeAreRefused) {
    const std::string d = freshDir("m");
    makePng(d);
    const std::string ok = "image: m.png\nresolution: 0.05\norigin: [1.0, 2.0, 0.0]\n";
    TMapSourceOptions s;
    s.map_file = d + "/m.yaml";
    for (const auto& [extra, what] : std::vector<std::pair<std::string, std::string>>{
             {"occupied_thresh: nan\n", "occupied_thresh = 'nan' must be in [0, 1]"},
             {"occupied_thresh: inf\n", "occupied_thresh = 'inf' must be in [0, 1]"},
             {"occupied_thresh: 2\n", "occupied_thresh = '2' must be in [0, 1]"},
             {"free_thresh: -0.1\n", "free_thresh = '-0.1' must be in [0, 1]"},
             {"free_thresh: 0.9\noccupied_thresh: 0.65\n", "free_thresh must be <"},
             {"negate: maybe\n", "negate = 'maybe' must be 0 or 1"}}) {
        writeFile(d + "/m.yaml", ok + extra);
        try {
            loadOccupancyGrid(s);
            ADD_FAILURE() << "accepted: " << extra;
        } catch (const CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    }
    writeFile(d + "/m.yaml",
              "image: m.png\nresolution: 1e-300\norigin: [1.0, 2.0, 0.0]\n");
    EXPECT_THROW(loadOccupancyGrid(s), CBadInputError);
    writeFile(d + "/m.yaml",
              "image: m.png\nresolution: 0.05\norigin: [1e300, 2.0, 0.0]\n");
    EXPECT_THROW(loadOccupancyGrid(s), CBadInputError);
}

// A corrupt .gridmap header is refused before MRPT allocates what it claims
// (a zeroed tail or resolution 0 used to make it ask for gigabytes).
TEST(GridIO, CorruptGridmapHeadersAreRefusedBeforeAllocating) {
    const std::string d = freshDir("gm");
    const std::string ok =
        readFile(sourcePath("datasets/corridor-doors/corridor.gridmap.gz"));
    std::string raw;
    {
        mrpt::io::CFileGZInputStream f(
            sourcePath("datasets/corridor-doors/corridor.gridmap.gz"));
        char buf[4096];
        for (size_t n; (n = f.Read(buf, sizeof(buf))) > 0;)
            raw.append(buf, n);
    }
    const size_t o = 1 + 31 + 2;  // name, version, bits per cell
    auto writeGz = [&](const std::string& name, const std::string& bytes) {
        mrpt::io::CFileGZOutputStream f(d + "/" + name);
        f.Write(bytes.data(), bytes.size());
        return d + "/" + name;
    };
    TMapSourceOptions s;
    auto refused = [&](const std::string& path, const std::string& what) {
        s.map_file = path;
        try {
            loadOccupancyGrid(s);
            ADD_FAILURE() << "accepted " << path;
        } catch (const CBadInputError& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    std::string huge = raw;
    const uint32_t big = 40000;
    std::memcpy(&huge[o], &big, 4);
    std::memcpy(&huge[o + 4], &big, 4);
    refused(writeGz("huge.gridmap.gz", huge), "40000 x 40000 cells");
    std::string zeroRes = raw;
    std::memset(&zeroRes[o + 24], 0, 4);
    refused(writeGz("res0.gridmap.gz", zeroRes), "resolution");
    refused(writeGz("cut.gridmap.gz", raw.substr(0, o + 28 + 1000)), "truncated");
    std::string zeroTail = raw;
    std::fill(zeroTail.begin() + o, zeroTail.end(), '\0');
    refused(writeGz("zeros.gridmap.gz", zeroTail), "not a readable MRPT .gridmap file");
    // The intact file loads to exactly what MRPT's own deserialization gives.
    s.map_file = writeGz("ok.gridmap.gz", raw);
    const auto ours = loadOccupancyGrid(s);
    mrpt::maps::COccupancyGridMap2D ref;
    {
        mrpt::io::CFileGZInputStream f(s.map_file);
        auto a = mrpt::serialization::archiveFrom(f);
        a >> ref;
    }
    ASSERT_EQ(ours.getSizeX(), ref.getSizeX());
    ASSERT_EQ(ours.getSizeY(), ref.getSizeY());
    EXPECT_EQ(ours.getXMin(), ref.getXMin());
    EXPECT_EQ(ours.getYMax(), ref.getYMax());
    EXPECT_EQ(ours.getResolution(), ref.getResolution());
    EXPECT_EQ(ours.getRawMap(), ref.getRawMap());
}

// Regression: the .gridmap.gz the fuzzer found (tests/fuzz/crashes/fuzz_map:
// its first byte picks the format, 2 = .gridmap.gz) made MRPT allocate 8.7 GB
// from a corrupt length AFTER the cells. Its header and cells are sound, so it
// loads, without reading the corrupt tail.
TEST(GridIO, FuzzerGridmapOomLoadsItsCellsOnly) {
    const std::string in =
        readFile(sourcePath("tests/fuzz/crashes/fuzz_map/oom-gridmap-gz-cell-count.bin"));
    ASSERT_GT(in.size(), 1u);
    ASSERT_EQ(uint8_t(in[0]) % 4, 2);
    const std::string f = freshDir("fz") + "/m.gridmap.gz";
    writeFile(f, in.substr(1));
    TMapSourceOptions s;
    s.map_file = f;
    const auto g = loadOccupancyGrid(s);
    EXPECT_LE(uint64_t(g.getSizeX()) * g.getSizeY(), 25'000'000u);
}
