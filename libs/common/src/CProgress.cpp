#include <risknav/common/CProgress.h>

#include <unistd.h>

#include <cmath>

namespace risknav::common {
CProgress::CProgress(const std::string& label, size_t total, const std::string& unit,
                     bool quiet, FILE* out)
    : m_label(label),
      m_unit(unit),
      m_total(total),
      m_quiet(quiet),
      m_tty(::isatty(::fileno(out)) != 0),
      m_out(out),
      m_start(std::chrono::steady_clock::now()),
      m_lastDraw(m_start) {}

std::string CProgress::formatLine(const std::string& label, size_t done, size_t total,
                                  double elapsedSec, const std::string& unit) {
    const double rate = elapsedSec > 0 ? done / elapsedSec : 0.0;
    char buf[256];
    if (total > 0 && done < total && rate > 0) {
        const int eta = static_cast<int>(std::ceil((total - done) / rate));
        std::snprintf(buf, sizeof(buf), "%s: %zu/%zu %s (%.0f %s/s, ETA %d:%02d)",
                      label.c_str(), done, total, unit.c_str(), rate, unit.c_str(),
                      eta / 60, eta % 60);
    } else
        std::snprintf(buf, sizeof(buf), "%s: %zu/%zu %s in %.1f s (%.0f %s/s)",
                      label.c_str(), done, total, unit.c_str(), elapsedSec, rate,
                      unit.c_str());
    return buf;
}

void CProgress::update(size_t done) {
    m_done = done;
    if (m_quiet || !m_tty)
        return;
    const auto now = std::chrono::steady_clock::now();
    if (now - m_lastDraw < std::chrono::milliseconds(200))
        return;
    m_lastDraw = now;
    const double el = std::chrono::duration<double>(now - m_start).count();
    std::fprintf(m_out, "\r%s\033[K",
                 formatLine(m_label, done, m_total, el, m_unit).c_str());
    std::fflush(m_out);
}

void CProgress::finish(const std::string& extra) {
    // The total may have been an estimate: the final line reports what was done.
    if (m_finished)
        return;
    m_finished = true;
    if (m_quiet)
        return;
    const double el =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    std::fprintf(m_out, "%s%s%s\n", m_tty ? "\r\033[K" : "",
                 formatLine(m_label, m_done, m_done, el, m_unit).c_str(), extra.c_str());
    std::fflush(m_out);
}

}  // namespace risknav::common
