#include <risknav/common/COutputDir.h>
#include <risknav/sim/CRawlogWriter.h>

#include <mrpt/serialization/CArchive.h>

#include <cerrno>
#include <stdexcept>

namespace risknav::sim {
CRawlogWriter::CRawlogWriter(const std::string& path, int level)
    : m_path(path), m_file(std::make_unique<mrpt::io::CFileGZOutputStream>()) {
    if (!m_file->open(path, level))
        throw common::writeFailure(path, errno);
}

void CRawlogWriter::write(const mrpt::obs::CActionCollection& actions,
                          const mrpt::obs::CSensoryFrame& sf) {
    try {
        auto a = mrpt::serialization::archiveFrom(*m_file);
        a << actions << sf;
    } catch (const std::exception&) {
        // MRPT says only "Cannot write bytes to stream!" (a full disk): the
        // file, and the system's reason as the failed write left it
        throw common::writeFailure(m_path, errno);
    }
    m_frames++;
}

void CRawlogWriter::close() {
    if (m_file)
        m_file->close();
    m_file.reset();
}

}  // namespace risknav::sim
