#include <risknav/localization/CRawlogReader.h>

#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace risknav::localization {
CRawlogReader::CRawlogReader(const std::string& path, double minStdXY,
                             double minStdPhiDeg)
    : m_path(path), m_minStdXY(minStdXY), m_minStdPhi(minStdPhiDeg * M_PI / 180.0) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw std::runtime_error(path + ": rawlog not found");
    m_size = std::filesystem::file_size(path, ec);
    m_in = std::make_unique<mrpt::io::CFileGZInputStream>();
    if (!m_in->open(path))
        throw std::runtime_error(path + ": cannot open rawlog");
}

uint64_t CRawlogReader::position() {
    return m_in ? m_in->getPosition() : m_size;
}

std::optional<TRawlogFrame> CRawlogReader::next() {
    using namespace mrpt::obs;
    auto arch = mrpt::serialization::archiveFrom(*m_in);
    while (!m_eof) {
        CActionCollection::Ptr act;
        CSensoryFrame::Ptr sf;
        CObservation::Ptr obs;
        const size_t before = m_entry;
        bool ok = false;
        try {
            ok = CRawlog::getActionObservationPairOrObservation(arch, act, sf, obs,
                                                                m_entry);
        } catch (const std::exception& e) {
            std::string msg = e.what();
            const auto m = msg.find("Message:");
            msg = msg.substr(m == std::string::npos ? 0 : m + 9);
            msg = msg.substr(0, msg.find('\n'));
            throw std::runtime_error(m_path + ": corrupt or truncated rawlog at entry " +
                                     std::to_string(before) + " (" + msg + ")");
        }
        if (!ok) {
            m_eof = true;
            break;
        }
        if (!obs) {
            TRawlogFrame f;
            f.actions = act;
            f.sf = sf;
            f.entry = m_entry > 0 ? m_entry - 1 : 0;
            f.timestamp =
                sf && sf->size() ? (*sf->begin())->timestamp : mrpt::Clock::time_point();
            return f;
        }
        // Observations-only format.
        if (auto odo = std::dynamic_pointer_cast<CObservationOdometry>(obs)) {
            const mrpt::poses::CPose2D now = odo->odometry;
            std::optional<TRawlogFrame> out;
            if (m_lastOdo && m_pending && m_pending->size()) {
                TRawlogFrame f;
                f.actions = CActionCollection::Create();
                CActionRobotMovement2D mv;
                CActionRobotMovement2D::TMotionModelOptions mo;
                mo.gaussianModel.minStdXY = m_minStdXY;
                mo.gaussianModel.minStdPHI = m_minStdPhi;
                mv.computeFromOdometry(now - *m_lastOdo, mo);
                mv.timestamp = odo->timestamp;
                f.actions->insert(mv);
                f.sf = m_pending;
                f.entry = m_entry > 0 ? m_entry - 1 : 0;
                f.timestamp = odo->timestamp;
                out = f;
            }
            if (!m_lastOdo || (m_pending && m_pending->size()))
                m_lastOdo = now;
            m_pending = CSensoryFrame::Create();
            if (out)
                return out;
            continue;
        }
        if (!m_pending)
            m_pending = CSensoryFrame::Create();
        m_pending->insert(obs);
    }
    return std::nullopt;
}

}  // namespace risknav::localization
