#pragma once
#include <risknav/localization/rawlog_scan.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace risknav::localization {
/** What MRPT may allocate while deserializing one rawlog entry:
 *  kEntryBudgetBase + kEntryBudgetPerByte x the bytes left in the
 *  (decompressed) file. A real entry's arrays and strings are stored in the
 *  file, so they cannot need more than a small multiple of what is left; the
 *  base covers fixed-size buffers. Lengths or counts beyond it are damage. */
constexpr std::uint64_t kEntryBudgetBase = 64ull << 20;
constexpr std::uint64_t kEntryBudgetPerByte = 16;
std::size_t rawlogEntryBudget(std::uint64_t bytesLeft);

/** One step of a rawlog: odometry increment (as an action) + what was sensed. */
struct TRawlogFrame {
    mrpt::obs::CActionCollection::Ptr actions;
    mrpt::obs::CSensoryFrame::Ptr sf;
    size_t entry = 0;  ///< rawlog entry index of the sensory frame
    mrpt::Clock::time_point timestamp;
};

/** Streams an MRPT rawlog, either format, in constant memory:
 *  - action / sensory-frame pairs are passed through;
 *  - observations-only logs are grouped: the observations after a
 *    CObservationOdometry (until the next one) become a sensory frame, and
 *    the odometry change up to it becomes a CActionRobotMovement2D (zero for
 *    the first; MRPT's Gaussian motion model, with minimum sigmas as
 *    pf-localization's [DummyOdometryParams]).
 * Errors (unreadable file, corrupt or truncated data) throw
 * std::runtime_error naming the entry index; frames read before stay valid.
 * Frames that cannot be real are errors where they appear (a flipped byte in
 * a gz stream may still decode): a valid range outside [0, maxRange] or not
 * finite, a non-finite sensor pose, aperture or odometry increment, an
 * odometry jump beyond 100 m in one frame, a timestamp before the previous
 * frame's, a null action or observation inside a frame.
 * Hostile files: the constructor reads the file once in a child process
 * (probeInChild) to find an entry MRPT 2.5 would segfault on, which then is
 * an error where it appears; each entry is read under a CAllocationBudget
 * (rawlogEntryBudget) sized by the decompressed bytes left (rawlogBytes). */
class CRawlogReader {
  public:
    explicit CRawlogReader(const std::string& path, double minStdXY = 0.01,
                           double minStdPhiDeg = 0.2);
    /** The next frame, or nullopt at the end of the file. */
    std::optional<TRawlogFrame> next();
    const std::string& path() const { return m_path; }

  private:
    /** The probe's reader: no probe of its own, reports entries read. */
    CRawlogReader(const std::string& path, double minStdXY, double minStdPhiDeg,
                  const TProbeProgress* progress);
    std::string m_path;
    std::unique_ptr<mrpt::io::CFileGZInputStream> m_in;
    size_t m_entry = 0;
    std::uint64_t m_bytes = 0;  ///< decompressed size (rawlogBytes)
    bool m_broken = false;      ///< the gzip stream breaks after m_bytes
    const TProbeProgress* m_progress = nullptr;
    std::optional<std::uint64_t> m_crashEntry;  ///< from the probe
    double m_minStdXY, m_minStdPhi;
    // observations-only state
    std::optional<TRawlogFrame> pendingFrame();
    /** Throws when the frame cannot be real (see the class comment). */
    void checkFrame(const TRawlogFrame& f);
    mrpt::Clock::time_point m_lastTime;
    std::optional<mrpt::poses::CPose2D> m_prevOdo, m_curOdo;
    mrpt::Clock::time_point m_curOdoTime;
    mrpt::obs::CSensoryFrame::Ptr m_pending;
    size_t m_pendingEntry = 0;
    bool m_eof = false;
};

}  // namespace risknav::localization
