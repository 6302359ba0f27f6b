#pragma once
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <memory>
#include <string>

namespace risknav::sim {
/** Streams an MRPT rawlog in the action / sensory-frame format (what
 * pf-localization and rawlog-edit read): gz-compressed CArchive of
 * alternating CActionCollection and CSensoryFrame objects. Constant memory:
 * nothing is kept after write(). */
class CRawlogWriter {
  public:
    explicit CRawlogWriter(const std::string& path, int gzCompressLevel = 1);
    void write(const mrpt::obs::CActionCollection& actions,
               const mrpt::obs::CSensoryFrame& sf);
    void close();
    size_t frames() const { return m_frames; }

  private:
    std::string m_path;
    std::unique_ptr<mrpt::io::CFileGZOutputStream> m_file;
    size_t m_frames = 0;
};

}  // namespace risknav::sim
