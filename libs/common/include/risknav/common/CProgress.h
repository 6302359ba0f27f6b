#pragma once
#include <chrono>
#include <cstdio>
#include <string>

namespace risknav::common {
/** Progress of long work on stderr. On a terminal: one self-overwriting line
 * "label: done/total (rate unit/s, ETA m:ss)", redrawn at most 5 times a
 * second. Not a terminal (CI, pipes): a single summary line at finish().
 * Quiet: nothing. */
class CProgress {
  public:
    CProgress(const std::string& label, size_t total, const std::string& unit, bool quiet,
              FILE* out = stderr);
    void update(size_t done);
    /** Prints the final line (also on non-terminals). Idempotent. */
    void finish(const std::string& extra = "");
    bool isTerminal() const { return m_tty; }

    /** The text of a progress line (pure: used by update() and tests). */
    static std::string formatLine(const std::string& label, size_t done, size_t total,
                                  double elapsedSec, const std::string& unit);

  private:
    std::string m_label, m_unit;
    size_t m_total, m_done = 0;
    bool m_quiet, m_tty, m_finished = false;
    FILE* m_out;
    std::chrono::steady_clock::time_point m_start, m_lastDraw;
};

}  // namespace risknav::common
