#include <risknav/common/CAllocationBudget.h>
#include <risknav/common/config_read.h>
#include <risknav/localization/CRawlogReader.h>
#include <risknav/localization/rawlog_scan.h>

#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace risknav::localization {
CRawlogReader::CRawlogReader(const std::string& path, double minStdXY,
                             double minStdPhiDeg)
    : CRawlogReader(path, minStdXY, minStdPhiDeg, nullptr) {
    // One pass through MRPT in a child process finds the entry, if any,
    // whose deserialization would kill this process (probe_in_child.h).
    m_crashEntry = common::probeInChild([&](const TProbeProgress& progress) {
        CRawlogReader probe(path, minStdXY, minStdPhiDeg, &progress);
        while (probe.next()) {
        }
    });
}

CRawlogReader::CRawlogReader(const std::string& path, double minStdXY,
                             double minStdPhiDeg, const TProbeProgress* progress)
    : m_path(path),
      m_progress(progress),
      m_minStdXY(minStdXY),
      m_minStdPhi(minStdPhiDeg * M_PI / 180.0) {
    if (const std::string why = common::fileProblem(path); !why.empty())
        throw std::runtime_error(path + ": rawlog " + why);
    const TRawlogSize size = rawlogBytes(path);
    m_bytes = size.bytes;
    m_broken = size.broken;
    m_in = std::make_unique<mrpt::io::CFileGZInputStream>();
    if (!m_in->open(path))
        throw std::runtime_error(path + ": cannot open rawlog");
}

std::size_t rawlogEntryBudget(std::uint64_t bytesLeft) {
    const std::uint64_t b = kEntryBudgetBase + kEntryBudgetPerByte * bytesLeft;
    return b > SIZE_MAX / 2 ? SIZE_MAX / 2 : static_cast<std::size_t>(b);
}

namespace {
std::string firstMessage(const std::exception& e) {
    std::string msg = e.what();
    const auto m = msg.find("Message:");
    msg = msg.substr(m == std::string::npos ? 0 : m + 8);
    msg = msg.substr(0, msg.find('\n'));
    const auto b = msg.find_first_not_of(' ');
    return b == std::string::npos ? msg : msg.substr(b);
}
}  // namespace

std::optional<TRawlogFrame> CRawlogReader::next() {
    using namespace mrpt::obs;
    // Objects are read one by one (not with CRawlog::getActionObservationPair...,
    // which prints and swallows a broken object as if the file had ended): a
    // clean end of file is CExceptionEOF at an object boundary, anything else
    // is a corrupt or truncated rawlog.
    auto arch = mrpt::serialization::archiveFrom(*m_in);
    auto readObject = [&](bool eofAllowed) -> mrpt::serialization::CSerializable::Ptr {
        if (m_crashEntry && m_entry == *m_crashEntry)
            throw std::runtime_error(
                m_path + ": corrupt rawlog at entry " + std::to_string(m_entry) +
                ": MRPT's deserializer crashes on it (a null or mistyped object "
                "inside; found by reading the file in a child process first)");
        mrpt::serialization::CSerializable::Ptr o;
        const std::uint64_t pos = m_in->getPosition();
        const std::uint64_t left = m_bytes > pos ? m_bytes - pos : 0;
        const std::size_t limit = rawlogEntryBudget(left);
        bool overBudget = false;
        try {
            // the budget covers MRPT's deserialization only (not our messages)
            risknav::common::CAllocationBudget budget(limit);
            try {
                o = arch.ReadObject();
            } catch (...) {
                overBudget = budget.exceeded();
                throw;
            }
            m_entry++;
            if (m_progress)
                (*m_progress)(m_entry);
        } catch (const mrpt::serialization::CExceptionEOF&) {
            if (m_broken)
                throw std::runtime_error(m_path + ": corrupt rawlog at entry " +
                                         std::to_string(m_entry) +
                                         ": the gzip stream breaks after " +
                                         std::to_string(m_bytes) + " bytes");
            if (eofAllowed)
                return nullptr;
            throw std::runtime_error(m_path + ": truncated rawlog at entry " +
                                     std::to_string(m_entry) +
                                     " (an action without its sensory frame)");
        } catch (const std::exception& e) {
            if (overBudget)
                throw std::runtime_error(
                    m_path + ": corrupt rawlog at entry " + std::to_string(m_entry) +
                    ": it asks for more than " + std::to_string(limit >> 20) +
                    " MiB, more than the " + std::to_string(left) +
                    " bytes left in the file can hold (lengths or counts in it are "
                    "damaged)");
            throw std::runtime_error(m_path + ": corrupt or truncated rawlog at entry " +
                                     std::to_string(m_entry) + " (" + firstMessage(e) +
                                     ")");
        }
        // MRPT serializes a null pointer as a valid "null object": in a rawlog
        // it is corruption, never an end of file (nor a frame to dereference).
        if (!o)
            throw std::runtime_error(m_path + ": corrupt rawlog at entry " +
                                     std::to_string(m_entry - 1) + " (a null object)");
        return o;
    };
    while (!m_eof) {
        const auto o = readObject(true);
        if (!o) {
            m_eof = true;
            break;
        }
        if (auto act = std::dynamic_pointer_cast<CActionCollection>(o)) {
            const auto next = readObject(false);
            auto sf = std::dynamic_pointer_cast<CSensoryFrame>(next);
            if (!sf)
                throw std::runtime_error(
                    m_path + ": corrupt rawlog at entry " + std::to_string(m_entry - 1) +
                    ": an action is followed by a " + next->GetRuntimeClass()->className +
                    ", not a sensory frame");
            TRawlogFrame f;
            f.actions = act;
            f.sf = sf;
            f.entry = m_entry - 1;
            f.timestamp = sf->size() && *sf->begin() ? (*sf->begin())->timestamp
                                                     : mrpt::Clock::time_point();
            checkFrame(f);
            return f;
        }
        if (std::dynamic_pointer_cast<CSensoryFrame>(o))
            continue;  // a leading frame without odometry: skipped
        auto obs = std::dynamic_pointer_cast<CObservation>(o);
        if (!obs)
            throw std::runtime_error(m_path + ": not a rawlog: entry " +
                                     std::to_string(m_entry - 1) + " is a " +
                                     o->GetRuntimeClass()->className);
        // Observations-only format: odometry k, then the observations taken
        // there. A frame = the motion from odometry k-1 to k (zero for the
        // first) + the observations after odometry k; it is complete when
        // odometry k+1 (or the end of the file) arrives.
        if (auto odo = std::dynamic_pointer_cast<CObservationOdometry>(obs)) {
            std::optional<TRawlogFrame> out = pendingFrame();
            m_prevOdo =
                m_curOdo ? m_curOdo : std::optional<mrpt::poses::CPose2D>(odo->odometry);
            m_curOdo = odo->odometry;
            m_curOdoTime = odo->timestamp;
            m_pending = CSensoryFrame::Create();
            m_pendingEntry = m_entry - 1;
            if (out) {
                checkFrame(*out);
                return out;
            }
            continue;
        }
        if (!m_pending)
            m_pending = CSensoryFrame::Create();
        m_pending->insert(obs);
    }
    // The last frame of an observations-only log.
    if (auto out = pendingFrame()) {
        m_pending.reset();
        checkFrame(*out);
        return out;
    }
    return std::nullopt;
}

void CRawlogReader::checkFrame(const TRawlogFrame& f) {
    using namespace mrpt::obs;
    auto bad = [&](const std::string& what) {
        throw std::runtime_error(m_path + ": corrupt rawlog at entry " +
                                 std::to_string(f.entry) + ": " + what);
    };
    auto num = [](double v) {
        char b[32];
        std::snprintf(b, sizeof(b), "%g", v);
        return std::string(b);
    };
    for (const auto& o : *f.sf)
        if (!o)
            bad("its sensory frame holds a null observation");
    for (const auto& a : *f.actions)
        if (!a.get_ptr())
            bad("its action collection holds a null action");
    for (const auto& o : *f.sf) {
        const auto scan = std::dynamic_pointer_cast<CObservation2DRangeScan>(o);
        if (!scan)
            continue;
        const std::string who = "scan '" + scan->sensorLabel + "'";
        const auto& sp = scan->sensorPose;
        if (!std::isfinite(sp.x()) || !std::isfinite(sp.y()) || !std::isfinite(sp.z()) ||
            !std::isfinite(sp.yaw()))
            bad(who + " has a non-finite sensor pose");
        if (!std::isfinite(scan->aperture) || !(scan->aperture > 0) ||
            scan->aperture > 2 * M_PI + 1e-3)
            bad(who + " has aperture " + num(scan->aperture) + " rad (not in (0, 2 pi])");
        if (!std::isfinite(scan->maxRange) || !(scan->maxRange > 0))
            bad(who + " has maxRange " + num(scan->maxRange));
        for (size_t i = 0; i < scan->getScanSize(); i++) {
            if (!scan->getScanRangeValidity(i))
                continue;
            const float r = scan->getScanRange(i);
            if (!std::isfinite(r) || r < 0 || r > scan->maxRange * 1.0001f)
                bad(who + " ray " + std::to_string(i) + " has range " + num(r) +
                    " (valid rays lie in [0, maxRange = " + num(scan->maxRange) + "])");
        }
    }
    for (const auto& a : *f.actions) {
        const auto mv = std::dynamic_pointer_cast<CActionRobotMovement2D>(a.get_ptr());
        if (!mv)
            continue;
        const auto d = mv->rawOdometryIncrementReading;
        if (!std::isfinite(d.x()) || !std::isfinite(d.y()) || !std::isfinite(d.phi()))
            bad("the odometry increment is not finite");
        if (std::hypot(d.x(), d.y()) > 100)
            bad("the odometry jumps " + num(std::hypot(d.x(), d.y())) +
                " m in one frame (more than 100 m)");
    }
    const bool timed =
        f.timestamp != mrpt::Clock::time_point() && f.timestamp != INVALID_TIMESTAMP;
    if (timed && m_lastTime != mrpt::Clock::time_point() && f.timestamp < m_lastTime)
        bad("its timestamp " + std::to_string(mrpt::Clock::toDouble(f.timestamp)) +
            " s is before the previous frame's " +
            std::to_string(mrpt::Clock::toDouble(m_lastTime)) + " s");
    if (timed)
        m_lastTime = f.timestamp;
}

std::optional<TRawlogFrame> CRawlogReader::pendingFrame() {
    using namespace mrpt::obs;
    if (!m_curOdo || !m_pending || m_pending->size() == 0)
        return std::nullopt;
    TRawlogFrame f;
    f.actions = CActionCollection::Create();
    CActionRobotMovement2D mv;
    CActionRobotMovement2D::TMotionModelOptions mo;
    mo.gaussianModel.minStdXY = m_minStdXY;
    mo.gaussianModel.minStdPHI = m_minStdPhi;
    mv.computeFromOdometry(*m_curOdo - *m_prevOdo, mo);
    mv.timestamp = m_curOdoTime;
    f.actions->insert(mv);
    f.sf = m_pending;
    f.entry = m_pendingEntry;
    f.timestamp = (*m_pending->begin())->timestamp;
    return f;
}

}  // namespace risknav::localization
