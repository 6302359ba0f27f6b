#include <risknav/localization/CRawlogReader.h>

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>

#include "test_support.h"

using namespace risknav::localization;
using mrpt::poses::CPose2D;

namespace {
// N frames of a robot driving an arc: odometry poses and one scan each
// (range i + k/100 on ray i, so scans are told apart).
struct TLog {
    std::vector<CPose2D> odo;
    std::vector<mrpt::obs::CObservation2DRangeScan::Ptr> scans;
};
TLog makeLog(size_t n) {
    TLog l;
    CPose2D p;
    for (size_t k = 0; k < n; k++) {
        l.odo.push_back(p);
        auto s = mrpt::obs::CObservation2DRangeScan::Create();
        s->sensorLabel = "LASER";
        s->timestamp = mrpt::Clock::fromDouble(1000.0 + 0.2 * k);
        s->resizeScan(5);
        for (size_t i = 0; i < 5; i++) {
            s->setScanRange(i, float(1 + i + k / 100.0));
            s->setScanRangeValidity(i, true);
        }
        l.scans.push_back(s);
        p = p + CPose2D(0.05, 0.0, 0.02);
    }
    return l;
}
// Reads every frame of a rawlog: how many were good, and the error (if any).
std::pair<size_t, std::string> readUntilError(const std::string& path) {
    size_t good = 0;
    try {
        CRawlogReader r(path);  // a file refused at open reads as 0 frames
        while (r.next())
            good++;
    } catch (const std::runtime_error& e) {
        return {good, e.what()};
    }
    return {good, ""};
}
}  // namespace

TEST(CRawlogReader, BothFormatsGiveTheSameFrames) {
    const auto log = makeLog(30);
    const std::string d = risknav::test::freshDir("rawlog");
    {
        // Action / sensory-frame pairs.
        mrpt::io::CFileGZOutputStream f(d + "/pairs.rawlog");
        auto a = mrpt::serialization::archiveFrom(f);
        for (size_t k = 0; k < log.odo.size(); k++) {
            mrpt::obs::CActionCollection acts;
            mrpt::obs::CActionRobotMovement2D mv;
            mv.computeFromOdometry(k ? log.odo[k] - log.odo[k - 1] : CPose2D(), {});
            acts.insert(mv);
            mrpt::obs::CSensoryFrame sf;
            sf.insert(log.scans[k]);
            a << acts << sf;
        }
    }
    {
        // Observations only: odometry k, then the scan taken there.
        mrpt::io::CFileGZOutputStream f(d + "/obsonly.rawlog");
        auto a = mrpt::serialization::archiveFrom(f);
        for (size_t k = 0; k < log.odo.size(); k++) {
            mrpt::obs::CObservationOdometry o;
            o.odometry = log.odo[k];
            o.timestamp = log.scans[k]->timestamp;
            a << o << *log.scans[k];
        }
    }
    CRawlogReader pairs(d + "/pairs.rawlog"), obsOnly(d + "/obsonly.rawlog");
    for (size_t k = 0; k < log.odo.size(); k++) {
        const auto fa = pairs.next(), fb = obsOnly.next();
        ASSERT_TRUE(fa && fb) << "frame " << k;
        const auto ia = fa->actions->getActionByClass<mrpt::obs::CActionRobotMovement2D>()
                            ->poseChange->getMeanVal();
        const auto ib = fb->actions->getActionByClass<mrpt::obs::CActionRobotMovement2D>()
                            ->poseChange->getMeanVal();
        EXPECT_NEAR(ia.x(), ib.x(), 1e-9) << k;
        EXPECT_NEAR(ia.y(), ib.y(), 1e-9) << k;
        EXPECT_NEAR(ia.phi(), ib.phi(), 1e-9) << k;
        const auto sa =
            fa->sf->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
        const auto sb =
            fb->sf->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
        ASSERT_TRUE(sa && sb);
        EXPECT_FLOAT_EQ(sa->getScanRange(0), sb->getScanRange(0))
            << "the scan of frame " << k;
    }
    EXPECT_FALSE(pairs.next());
    EXPECT_FALSE(obsOnly.next());
}

TEST(CRawlogReader, TruncationIsAnErrorWithTheEntryIndex) {
    const auto log = makeLog(200);
    const std::string d = risknav::test::freshDir("rawlog");
    {
        mrpt::io::CFileGZOutputStream f(d + "/full.rawlog");
        auto a = mrpt::serialization::archiveFrom(f);
        for (size_t k = 0; k < log.odo.size(); k++) {
            mrpt::obs::CActionCollection acts;
            mrpt::obs::CActionRobotMovement2D mv;
            mv.computeFromOdometry(CPose2D(0.05, 0, 0), {});
            acts.insert(mv);
            mrpt::obs::CSensoryFrame sf;
            sf.insert(log.scans[k]);
            a << acts << sf;
        }
    }
    const std::string full = risknav::test::readFile(d + "/full.rawlog");
    risknav::test::writeFile(d + "/cut.rawlog", full.substr(0, full.size() / 2));
    CRawlogReader r(d + "/cut.rawlog");
    size_t frames = 0;
    try {
        while (r.next())
            frames++;
        FAIL() << "a truncated rawlog read as complete";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("at entry"), std::string::npos) << e.what();
    }
    EXPECT_GT(frames, 10u);
    EXPECT_LT(frames, 200u);
    EXPECT_THROW(CRawlogReader(d + "/missing.rawlog"), std::runtime_error);
}

TEST(CRawlogReader, FramesThatCannotBeRealAreErrorsWhereTheyAppear) {
    enum class TBad { NegativeRange, BeyondMaxRange, NanOdometry, TimeBackwards };
    for (const auto bad : {TBad::NegativeRange, TBad::BeyondMaxRange, TBad::NanOdometry,
                           TBad::TimeBackwards}) {
        auto log = makeLog(12);
        const size_t k = 7;  // the damaged frame
        CPose2D inc(0.05, 0.0, 0.02);
        if (bad == TBad::NegativeRange)
            log.scans[k]->setScanRange(2, -3.0f);
        if (bad == TBad::BeyondMaxRange)
            log.scans[k]->setScanRange(2, 1000.0f);
        if (bad == TBad::NanOdometry)
            inc = CPose2D(std::nan(""), 0.0, 0.0);
        if (bad == TBad::TimeBackwards)
            log.scans[k]->timestamp = mrpt::Clock::fromDouble(900.0);
        const std::string f = risknav::test::freshDir("bad") + "/bad.rawlog";
        {
            mrpt::io::CFileGZOutputStream out(f);
            auto a = mrpt::serialization::archiveFrom(out);
            for (size_t i = 0; i < log.odo.size(); i++) {
                mrpt::obs::CActionCollection acts;
                mrpt::obs::CActionRobotMovement2D mv;
                mv.computeFromOdometry(i == k ? inc : CPose2D(0.05, 0.0, 0.02), {});
                acts.insert(mv);
                mrpt::obs::CSensoryFrame sf;
                sf.insert(log.scans[i]);
                a << acts << sf;
            }
        }
        const auto [good, err] = readUntilError(f);
        EXPECT_EQ(good, k) << int(bad);
        EXPECT_NE(err.find("corrupt rawlog at entry " + std::to_string(2 * k + 1)),
                  std::string::npos)
            << err;
        const char* why[] = {"has range -3", "has range 1000", "not finite",
                             "before the previous frame"};
        EXPECT_NE(err.find(why[int(bad)]), std::string::npos) << err;
    }
}

TEST(CRawlogReader, ANullObjectIsCorruptionNotTheEnd) {
    // MRPT writes a null pointer as a "null object". After an action it used to
    // crash the reader; between frames it read as a clean end of file.
    const auto log = makeLog(6);
    for (const bool afterAction : {true, false}) {
        const std::string f = risknav::test::freshDir("null") + "/null.rawlog";
        {
            mrpt::io::CFileGZOutputStream out(f);
            auto a = mrpt::serialization::archiveFrom(out);
            for (size_t k = 0; k < log.odo.size(); k++) {
                mrpt::obs::CActionCollection acts;
                mrpt::obs::CActionRobotMovement2D mv;
                mv.computeFromOdometry(CPose2D(0.05, 0, 0), {});
                acts.insert(mv);
                mrpt::obs::CSensoryFrame sf;
                sf.insert(log.scans[k]);
                if (k == 3 && !afterAction)
                    a.WriteObject(nullptr);
                a << acts;
                if (k == 3 && afterAction)
                    a.WriteObject(nullptr);
                else
                    a << sf;
            }
        }
        const auto [good, err] = readUntilError(f);
        EXPECT_EQ(good, 3u) << afterAction;
        EXPECT_NE(err.find("a null object"), std::string::npos) << err;
    }
}

namespace {
std::string serialized(const mrpt::serialization::CSerializable& o) {
    mrpt::io::CMemoryStream m;
    auto a = mrpt::serialization::archiveFrom(m);
    a << o;
    return std::string(static_cast<const char*>(m.getRawBufferData()),
                       m.getTotalBytesCount());
}
}  // namespace

TEST(CRawlogReader, ANullPosePdfIsAnErrorWhereItAppears) {
    // An action estimated by scan matching carries its PDF object; a null one
    // makes MRPT 2.5 segfault (the fuzzer found the same with a CPose2D in its
    // place). Made here by replacing the PDF's bytes with a null object.
    mrpt::obs::CActionRobotMovement2D mv;
    mv.computeFromOdometry(CPose2D(0.05, 0, 0), {});
    mv.estimationMethod = mrpt::obs::CActionRobotMovement2D::emScan2DMatching;
    mrpt::obs::CActionCollection acts;
    acts.insert(mv);
    std::string bytes = serialized(acts);
    const std::string pdf = serialized(*mv.poseChange.get_ptr());
    const auto at = bytes.find(pdf);
    ASSERT_NE(at, std::string::npos);
    const std::string good = bytes;
    bytes.replace(at, pdf.size(), std::string("\x87nullptr\x88", 9));

    const auto log = makeLog(4);
    mrpt::obs::CSensoryFrame sf;
    sf.insert(log.scans[0]);
    const std::string d = risknav::test::freshDir("nullpdf");
    for (const bool broken : {false, true}) {
        const std::string f = d + (broken ? "/bad.rawlog" : "/good.rawlog");
        std::string content;
        for (int k = 0; k < 3000; k++)
            content += (broken && k == 2500 ? bytes : good) + serialized(sf);
        risknav::test::writeFile(f, content);
        const auto [n, err] = readUntilError(f);
        if (!broken) {
            EXPECT_EQ(n, 3000u);
            EXPECT_EQ(err, "");
        } else {
            EXPECT_EQ(n, 2500u);  // the frames before it are read
            EXPECT_NE(err.find("bad.rawlog: corrupt rawlog at entry 5000: MRPT's "
                               "deserializer crashes on it"),
                      std::string::npos)
                << err;
        }
    }
}

TEST(CRawlogReader, CountsFromTheFileCannotAllocateBeyondIt) {
    // A 37-byte file whose action collection claims 2^32 - 1 actions made MRPT
    // resize a deque of 4 G pointers; a scan whose label length is 3 GB asked
    // for 3 GB (fuzzer findings). Both now stop at the entry's budget.
    const std::string d = risknav::test::freshDir("budget");
    mrpt::obs::CActionCollection acts;
    std::string bytes = serialized(acts);  // header, version, count 0, end
    const auto countAt = bytes.size() - 5;
    bytes.replace(countAt, 4, std::string("\xff\xff\xff\xff", 4));
    risknav::test::writeFile(d + "/count.rawlog", bytes);
    auto [n, err] = readUntilError(d + "/count.rawlog");
    EXPECT_EQ(n, 0u);
    EXPECT_NE(
        err.find("count.rawlog: corrupt rawlog at entry 0: it asks for more than 64 MiB"),
        std::string::npos)
        << err;

    const auto log = makeLog(2);
    mrpt::obs::CSensoryFrame sf;
    sf.insert(log.scans[0]);
    std::string s = serialized(sf);
    const auto label = s.find("LASER");
    ASSERT_NE(label, std::string::npos);
    s.replace(label - 4, 4, std::string("\x00\x00\x00\xc0", 4));  // 3 GiB
    mrpt::obs::CActionRobotMovement2D mv;
    mv.computeFromOdometry(CPose2D(0.05, 0, 0), {});
    mrpt::obs::CActionCollection a2;
    a2.insert(mv);
    risknav::test::writeFile(d + "/label.rawlog", serialized(a2) + s);
    std::tie(n, err) = readUntilError(d + "/label.rawlog");
    EXPECT_EQ(n, 0u);
    EXPECT_NE(err.find("corrupt rawlog at entry 1: it asks for more than"),
              std::string::npos)
        << err;
}

TEST(CRawlogReader, TheFuzzersFindingsGiveOneClearError) {
    for (const std::string f : {"segv-null-deref-CActionRobotMovement2D.rawlog.gz",
                                "oom-CObservation2DRangeScan-string-length.rawlog",
                                "timeout-gzread-error-loops.rawlog.gz",
                                "oom-scan-size-mrpt-aligned-alloc.rawlog"}) {
        const std::string path =
            risknav::test::sourcePath("tests/fuzz/crashes/fuzz_rawlog/" + f);
        const auto [n, err] = readUntilError(path);
        EXPECT_NE(err.find(f + ": corrupt"), std::string::npos) << err;
    }
}

TEST(CRawlogReader, ANullActionOrObservationInAFrameIsCorruption) {
    const auto log = makeLog(2);
    const std::string d = risknav::test::freshDir("nullitem");
    for (const bool inActions : {true, false}) {
        mrpt::obs::CActionRobotMovement2D mv;
        mv.computeFromOdometry(CPose2D(0.05, 0, 0), {});
        mrpt::obs::CActionCollection acts;
        acts.insert(mv);
        mrpt::obs::CSensoryFrame sf;
        sf.insert(log.scans[0]);
        std::string a = serialized(acts), s = serialized(sf);
        std::string& target = inActions ? a : s;
        const std::string item = inActions ? serialized(mv) : serialized(*log.scans[0]);
        const auto at = target.find(item);
        ASSERT_NE(at, std::string::npos);
        target.replace(at, item.size(), std::string("\x87nullptr\x88", 9));
        const std::string f = d + (inActions ? "/a.rawlog" : "/o.rawlog");
        risknav::test::writeFile(f, a + s);
        const auto [n, err] = readUntilError(f);
        EXPECT_EQ(n, 0u);
        // MRPT itself crashes on a null action (found by the probe); a null
        // observation it reads, and the reader refuses
        EXPECT_NE(
            err.find(inActions ? "entry 0: MRPT's deserializer crashes"
                               : "entry 1: its sensory frame holds a null observation"),
            std::string::npos)
            << err;
    }
}

TEST(CRawlogReader, EveryKeptFuzzerInputEndsCleanly) {
    // tests/fuzz/crashes/fuzz_rawlog: every input the fuzzer found a crash,
    // hang or memory blow-up with reads to an error or to its end; none
    // kills the test (a crash would), none takes long (a hang would time out)
    const std::string dir = risknav::test::sourcePath("tests/fuzz/crashes/fuzz_rawlog");
    size_t n = 0;
    for (const auto& f : risknav::test::listDir(dir)) {
        const auto [frames, err] = readUntilError(dir + "/" + f);
        (void)frames;
        if (!err.empty()) {
            EXPECT_NE(err.find(f), std::string::npos) << err;  // names the file
        }
        n++;
    }
    EXPECT_GE(n, 5u);
}
