// The map readers on damaged and unusual files: each case must end in one
// CBadInputError naming the file (never a signal, an escaping bad_alloc or
// an allocation the file cannot justify), or load what MRPT itself loads.
#include <risknav/common/CBadInputError.h>
#include <risknav/common/grid_io.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

using namespace risknav::common;
using namespace risknav::test;

namespace {
/** The CBadInputError message loading `file` gives ("" if it loads). */
std::string refusal(const std::string& file, double simplemapRes = 0.1) {
    TMapSourceOptions s;
    s.map_file = file;
    s.simplemap_resolution = simplemapRes;
    try {
        loadOccupancyGrid(s);
    } catch (const CBadInputError& e) {
        return e.what();
    }
    return "";
}

std::string le32(uint32_t v) {
    std::string s(4, '\0');
    std::memcpy(&s[0], &v, 4);
    return s;
}
std::string f32(float v) {
    std::string s(4, '\0');
    std::memcpy(&s[0], &v, 4);
    return s;
}

/** The bytes MRPT writes for `obj` (object header, data, end flag). */
std::string serialized(const mrpt::serialization::CSerializable& obj) {
    mrpt::io::CMemoryStream m;
    auto a = mrpt::serialization::archiveFrom(m);
    a << obj;
    return std::string(static_cast<const char*>(m.getRawBufferData()),
                       m.getTotalBytesCount());
}

/** One keyframe's sensory frame: a 181-ray scan of ranges `r`. */
mrpt::obs::CSensoryFrame frameWithScan(float r) {
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    scan->aperture = float(M_PI);
    scan->resizeScanAndAssign(181, r, true);
    mrpt::obs::CSensoryFrame sf;
    sf.insert(scan);
    return sf;
}

/** A simplemap stream: CSimpleMap header of `version`, the entry count, then
 * `body` (the keyframes' objects). */
std::string simplemapBytes(uint8_t version, uint32_t count, const std::string& body) {
    const std::string name = "mrpt::maps::CSimpleMap";
    return std::string(1, char(0x80 | name.size())) + name + char(version) + le32(count) +
           body + '\x88';
}

std::string writeGz(const std::string& path, const std::string& bytes) {
    mrpt::io::CFileGZOutputStream f(path);
    f.Write(bytes.data(), bytes.size());
    return path;
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}
}  // namespace

// MRPT 2.5 segfaults on a simplemap keyframe whose pose is null or of another
// class (version 0 files: CPose3DPDF::createFrom2D(*pose)): the reader learns
// that in a forked child and refuses the file.
TEST(MapReaders, SimplemapWithMistypedOrNullObjectsIsBadInput) {
    const std::string d = freshDir("smwrong");
    const auto sf = serialized(frameWithScan(3.0f));
    mrpt::obs::CObservationOdometry odo;
    const std::string nullObj = std::string(1, char(0x80 | 7)) + "nullptr";
    for (const auto& [name, body] : std::vector<std::pair<std::string, std::string>>{
             {"odometry-as-pose-v0", serialized(odo) + sf},
             {"null-pose-v0", nullObj + sf},
             {"null-pose-v1", nullObj + sf},
             {"scan-as-frame-v1",
              serialized(mrpt::poses::CPose3DPDFGaussian()) +
                  serialized(*frameWithScan(1.0f).getObservationByIndex(0))}}) {
        const uint8_t version = contains(name, "v0") ? 0 : 1;
        const std::string f =
            writeGz(d + "/" + name + ".simplemap", simplemapBytes(version, 1, body));
        const std::string why = refusal(f);
        EXPECT_TRUE(contains(why, f + ": ")) << name << ": " << why;
    }
}

// An entry count of 2^32 - 1 in a file of a few bytes: MRPT resized its
// keyframe vector to it (memory to the limit); the budget refuses it.
TEST(MapReaders, SimplemapCountsBeyondTheFileAreRefused) {
    const std::string d = freshDir("smcount");
    const std::string f =
        writeGz(d + "/huge.simplemap", simplemapBytes(1, 0xFFFFFFFFu, ""));
    const std::string why = refusal(f);
    EXPECT_TRUE(contains(why, "its counts ask for more than")) << why;
}

// simplemap_resolution 0.001 is in its documented range, but MRPT's grid of
// the demo map at 1 mm is billions of cells (std::bad_alloc escaped): the
// extent is computed from poses and scans first and the key is named.
TEST(MapReaders, SimplemapGridBeyond25MCellsNamesTheResolutionKey) {
    TMapSourceOptions s;
    s.map_file = "/usr/share/mrpt/datasets/localization_demo.simplemap.gz";
    s.simplemap_resolution = 0.001;
    s.section = "AfraidLearn";
    try {
        loadOccupancyGrid(s);
        FAIL() << "accepted";
    } catch (const CBadInputError& e) {
        const std::string why = e.what();
        EXPECT_TRUE(contains(why, "[AfraidLearn] simplemap_resolution = 0.001 m")) << why;
        EXPECT_TRUE(contains(why, "more than 25 M cells")) << why;
        EXPECT_EQ(why.find('\n'), std::string::npos);
    }
    // a sound simplemap built here loads, its grid covering its scans
    const std::string d = freshDir("smok");
    mrpt::maps::CSimpleMap sm;
    for (int k = 0; k < 3; k++) {
        auto pose = mrpt::poses::CPose3DPDFGaussian::Create();
        pose->mean = mrpt::poses::CPose3D(k * 2.0, 1.0, 0, 0, 0, 0);
        sm.insert(pose, mrpt::obs::CSensoryFrame::Create(frameWithScan(3.0f)));
    }
    ASSERT_TRUE(sm.saveToFile(d + "/ok.simplemap.gz"));
    s.map_file = d + "/ok.simplemap.gz";
    s.simplemap_resolution = 0.05;
    const auto g = loadOccupancyGrid(s);
    EXPECT_LE(g.getXMin(), -3.0);
    EXPECT_GE(g.getXMax(), 7.0);
    // the lowest P(free) within a cell of (x, y): the rays' ends are not
    // exactly on the axes
    auto lowestNear = [&](double x, double y) {
        float p = 1;
        for (const double dx : {-0.05, 0.0, 0.05})
            for (const double dy : {-0.05, 0.0, 0.05})
                p = std::min(p, g.getPos(x + dx, y + dy));
        return p;
    };
    EXPECT_LT(lowestNear(7.0, 1.0), 0.45f);  // the wall 3 m ahead of the last keyframe
    EXPECT_GT(g.getPos(6.0, 1.0), 0.55f);    // free space before it (one update each)
}

// A .gridmap header of 1 x 1 cells whose bounds span 2 km at 1 mm: MRPT's
// setSize would allocate from the bounds (4e12 cells) before any check.
TEST(MapReaders, GridmapSizeMustMatchItsBounds) {
    const std::string d = freshDir("gmbounds");
    const std::string name = "mrpt::maps::COccupancyGridMap2D";
    const std::string head =
        std::string(1, char(0x80 | name.size())) + name + '\x06' + '\x08';
    const std::string bad = head + le32(1) + le32(1) + f32(-1000) + f32(1000) +
                            f32(-1000) + f32(1000) + f32(0.001f) + std::string(64, '\0');
    const std::string why = refusal(writeGz(d + "/wide.gridmap.gz", bad));
    EXPECT_TRUE(contains(why, "does not match its bounds")) << why;
    // a header consistent with its bounds but beyond 25 M cells
    const std::string big = head + le32(10000) + le32(10000) + f32(0) + f32(1000) +
                            f32(0) + f32(1000) + f32(0.1f) + std::string(64, '\0');
    EXPECT_TRUE(
        contains(refusal(writeGz(d + "/big.gridmap.gz", big)), "10000 x 10000 cells"));
}

// MRPT's own dataset map is serialization version 3 with an object header
// naming the class without namespace: read, cell for cell as MRPT reads it.
TEST(MapReaders, MrptMalagaCampusGridmapVersion3) {
    const std::string f = "/usr/share/mrpt/datasets/2006-MalagaCampus.gridmap.gz";
    ASSERT_TRUE(std::filesystem::is_regular_file(f)) << "mrpt-common is not installed";
    TMapSourceOptions s;
    s.map_file = f;
    const auto ours = loadOccupancyGrid(s);
    mrpt::maps::COccupancyGridMap2D ref;
    {
        mrpt::io::CFileGZInputStream in(f);
        auto a = mrpt::serialization::archiveFrom(in);
        a >> ref;
    }
    ASSERT_EQ(ours.getSizeX(), ref.getSizeX());
    ASSERT_EQ(ours.getSizeY(), ref.getSizeY());
    EXPECT_EQ(ours.getXMin(), ref.getXMin());
    EXPECT_EQ(ours.getYMin(), ref.getYMin());
    EXPECT_EQ(ours.getXMax(), ref.getXMax());
    EXPECT_EQ(ours.getYMax(), ref.getYMax());
    EXPECT_EQ(ours.getResolution(), ref.getResolution());
    // the dataset's own figures (MRPT_NOTES: 1888 x 2738 cells at 0.08 m)
    EXPECT_EQ(ours.getSizeX(), 1888u);
    EXPECT_EQ(ours.getSizeY(), 2738u);
    EXPECT_FLOAT_EQ(ours.getResolution(), 0.08f);
    EXPECT_EQ(ours.getRawMap(), ref.getRawMap());
}

// Versions 0 to 2 stored probabilities, not log-odds, and version 0 has no
// bits-per-cell byte; before MRPT 0.5.5 the object header was 32-bit: every
// variant MRPT 2.5 reads gives the cells MRPT gives.
TEST(MapReaders, OldGridmapVersionsReadAsMrptReadsThem) {
    const std::string d = freshDir("gmold");
    std::string cells;
    for (int i = 0; i < 40 * 30; i++)
        cells += char(uint8_t(i * 7));
    const std::string geom =
        le32(40) + le32(30) + f32(-1) + f32(1) + f32(0) + f32(1.5f) + f32(0.05f);
    const std::string name = "COccupancyGridMap2D";
    const std::string newHead = std::string(1, char(0x80 | name.size())) + name;
    const std::string oldHead = le32(uint32_t(name.size())) + name;
    for (const auto& [label, bytes] : std::vector<std::pair<std::string, std::string>>{
             {"v0", newHead + '\0' + geom + cells + '\x88'},
             {"v0-old-header", oldHead + le32(0) + geom + cells}}) {
        const std::string f = writeGz(d + "/" + label + ".gridmap.gz", bytes);
        TMapSourceOptions s;
        s.map_file = f;
        const auto ours = loadOccupancyGrid(s);
        mrpt::maps::COccupancyGridMap2D ref;
        mrpt::io::CFileGZInputStream in(f);
        auto a = mrpt::serialization::archiveFrom(in);
        a >> ref;
        ASSERT_EQ(ours.getSizeX(), ref.getSizeX()) << label;
        EXPECT_EQ(ours.getRawMap(), ref.getRawMap()) << label;
    }
    // 16-bit cells (version 2, probabilities): MRPT keeps the high byte
    std::string wide;
    for (int i = 0; i < 40 * 30; i++)
        wide += std::string("\x00", 1) + char(i % 2 ? 255 : 0);
    const std::string v2 =
        newHead + '\x02' + '\x10' + geom + wide + std::string(200, '\0');
    TMapSourceOptions s;
    s.map_file = writeGz(d + "/v2-16.gridmap.gz", v2);
    const auto g = loadOccupancyGrid(s);
    EXPECT_NEAR(g.getCell(0, 0), 0.0f, 0.02f);
    EXPECT_NEAR(g.getCell(1, 0), 1.0f, 0.02f);
    // a version MRPT 2.5 does not read is named
    EXPECT_TRUE(contains(
        refusal(writeGz(d + "/v7.gridmap.gz", newHead + '\x07' + '\x08' + geom + cells)),
        "serialization version 7; MRPT 2.5 reads 0 to 6"));
}

// Every image format risknav decodes has its size read from its header
// first (a 162-byte JPEG can claim 30000 x 30000 px, an 8000 x 8000 TIFF
// decoded whole took 2 GB); other formats are refused.
TEST(MapReaders, ImageSizesAreReadFromEveryHeaderBeforeDecoding) {
    const std::string d = freshDir("imgsize");
    // JPEG: SOI, an APP0 segment, SOF0 of 30000 x 30000, 3 components
    std::string jpeg =
        "\xFF\xD8\xFF\xE0" +
        std::string("\x00\x10JFIF\x00\x01\x01\x00\x00\x01\x00\x01\x00\x00", 16);
    jpeg += std::string(
        "\xFF\xC0\x00\x11\x08\x75\x30\x75\x30\x03\x01\x22\x00\x02\x11\x01\x03\x11\x01",
        19);
    jpeg += std::string(162 - jpeg.size(), '\0');
    writeFile(d + "/huge.jpg", jpeg);
    // TIFF (little- and big-endian): one IFD, ImageWidth / ImageLength 8000
    std::string tiffLe = std::string("II*\0", 4) + le32(8) + std::string("\x02\x00", 2);
    tiffLe += std::string("\x00\x01\x03\x00\x01\x00\x00\x00\x40\x1F\x00\x00", 12);
    tiffLe += std::string("\x01\x01\x04\x00\x01\x00\x00\x00\x40\x1F\x00\x00", 12);
    tiffLe += le32(0);
    writeFile(d + "/huge.tif", tiffLe);
    std::string tiffBe = std::string("MM\0*\0\0\0\x08\0\x01", 10);
    tiffBe += std::string("\x01\x00\x00\x03\x00\x00\x00\x01\x1F\x40\x00\x00", 12);
    writeFile(d + "/wide.tiff", tiffBe);  // width only: no size
    writeFile(d + "/huge.ppm",
              "P6\n# a comment longer than the old 64-byte window of the reader\n9000 "
              "9000\n255\n");
    writeFile(d + "/long.pgm", "P5 99999999999999999999 1 255\n");  // one number, not two
    writeFile(d + "/map.gif", "GIF89a\x10\x00\x10\x00");
    for (const auto& [f, what] : std::vector<std::pair<std::string, std::string>>{
             {"huge.jpg", "30000 x 30000 px, more than 25 M cells"},
             {"huge.tif", "8000 x 8000 px, more than 25 M cells"},
             {"wide.tiff", "a TIFF header without its size"},
             {"huge.ppm", "9000 x 9000 px, more than 25 M cells"},
             {"long.pgm", "1099511627776 x 1 px, more than 25 M cells"},
             {"map.gif", "cannot read the map image (not a PNG"}}) {
        const std::string why = refusal(d + "/" + f);
        EXPECT_TRUE(contains(why, d + "/" + f + ": ") && contains(why, what))
            << f << ": " << why;
        EXPECT_EQ(why.find('\n'), std::string::npos);
    }
    // real files of the formats load (their headers read right)
    cv::Mat img(20, 30, CV_8UC1, cv::Scalar(255));
    for (const std::string ext : {".jpg", ".tif", ".bmp", ".pgm"}) {
        const std::string f = d + "/ok" + ext;
        ASSERT_TRUE(cv::imwrite(f, img)) << ext;
        TMapSourceOptions s;
        s.map_file = f;
        const auto g = loadOccupancyGrid(s);
        EXPECT_EQ(g.getSizeX(), 30u) << ext;
        EXPECT_EQ(g.getSizeY(), 20u) << ext;
    }
}

// A PGM's white is its header's maximum value (the format's definition, and
// how Nav2's map_server reads it): a map saved with maximum 100 is the same
// map as one saved with 255, its 50 the middle grey.
TEST(MapReaders, PgmSamplesAreScaledByTheHeadersMaximum) {
    const std::string d = freshDir("maxval");
    for (const int maxval : {255, 100, 1}) {
        // 4 x 2 px: top row white, black, white, black; bottom row grey
        const int grey = maxval / 2;
        std::string px;
        for (const int v : {maxval, 0, maxval, 0, grey, grey, grey, grey})
            px += char(v);
        const std::string f = d + "/m" + std::to_string(maxval) + ".pgm";
        writeFile(f, "P5\n4 2\n" + std::to_string(maxval) + "\n" + px);
        TMapSourceOptions s;
        s.map_file = f;
        const auto g = loadOccupancyGrid(s);
        ASSERT_EQ(g.getSizeX(), 4u);
        // MRPT's cells hold p(free): white free, black occupied (row y 1 = top)
        EXPECT_GT(g.getCell(0, 1), 0.99f) << maxval;
        EXPECT_LT(g.getCell(1, 1), 0.01f) << maxval;
        EXPECT_NEAR(g.getCell(0, 0), double(grey) / maxval, 0.02) << maxval;
    }
}

// ROS map YAML parsed as YAML: a key given twice, an origin that is not three
// numbers, are refused naming the file, line and key; a '#' inside a plain
// scalar is part of it.
TEST(MapReaders, RosYamlIsParsedAsYaml) {
    const std::string d = freshDir("yaml");
    cv::Mat img(20, 40, CV_8UC1, cv::Scalar(255));
    ASSERT_TRUE(cv::imwrite(d + "/corridor#1.png", img));
    const std::string f = d + "/m.yaml";
    TMapSourceOptions s;
    s.map_file = f;
    writeFile(
        f, "image: corridor#1.png  # a comment\nresolution: 0.05\norigin: [1, 2, 0]\n");
    EXPECT_EQ(loadOccupancyGrid(s).getSizeX(), 40u);
    for (const auto& [text, what] : std::vector<std::pair<std::string, std::string>>{
             {"image: corridor#1.png\nresolution: 0.05\norigin: [0, 0, 0]\nresolution: "
              "0.1\n",
              ":4: key 'resolution' given twice (also on line 2)"},
             {"image: corridor#1.png\nresolution: 0.05\norigin: [0, 0, abc]\n",
              ":3: origin: 'abc' is not a number"},
             {"image: corridor#1.png\nresolution: 0.05\norigin: [0, 0, nan]\n",
              ":3: origin: 'nan' is not a number"},
             {"image: corridor#1.png\nresolution: 0.05\norigin: [0, 0]\n",
              ":3: origin must be a list [x, y, yaw]"},
             {"image: corridor#1.png\nresolution: 0.05\norigin: [0, 0, 0.5]\n",
              "yaw != 0 is not supported"},
             {"image: corridor#1.png\nresolution: [0.05]\norigin: [0, 0, 0]\n",
              ":2: resolution must be a single value"},
             {"image: corridor#1.png\nresolution: 0x10\norigin: [0, 0, 0]\n",
              ":2: resolution = '0x10' is not a number"},
             {"image: \"corridor#1.png\\0.x\"\nresolution: 0.05\norigin: [0, 0, 0]\n",
              ":1: a value with a NUL character"},
             {"image: [corridor\n", "not YAML"},
             {"- image\n", "not a mapping of keys"},
             {"image: m.png\n---\nimage: n.png\n", "more than one YAML document"}}) {
        writeFile(f, text);
        const std::string why = refusal(f);
        EXPECT_TRUE(contains(why, f) && contains(why, what)) << text << " -> " << why;
        EXPECT_EQ(why.find('\n'), std::string::npos) << why;
    }
}

// A fuzzer finding (FuzzReplay.fuzz_simplemap): a scan with a negative range
// made MRPT draw the ray backwards off the grid, an assertion escaping as
// std::logic_error (exit 1, a multi-line MRPT message).
TEST(MapReaders, SimplemapNegativeRangeIsBadInput) {
    const std::string d = freshDir("smneg");
    mrpt::maps::CSimpleMap sm;
    auto sf = mrpt::obs::CSensoryFrame::Create(frameWithScan(2.0f));
    auto scan = sf->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
    scan->setScanRange(5, -500.0f);
    sm.insert(mrpt::poses::CPose3DPDFGaussian::Create(), sf);
    ASSERT_TRUE(sm.saveToFile(d + "/neg.simplemap.gz"));
    const std::string why = refusal(d + "/neg.simplemap.gz");
    EXPECT_TRUE(contains(why, "keyframe 0: a scan range is negative or not finite"))
        << why;
}
