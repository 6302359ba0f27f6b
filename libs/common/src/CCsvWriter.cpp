#include <risknav/common/CCsvWriter.h>
#include <risknav/common/COutputDir.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace risknav::common {
CCsvWriter::CCsvWriter(const std::string& path, const std::vector<std::string>& header)
    : m_path(path), m_out(path, std::ios::trunc), m_columns(header.size()) {
    if (!m_out.good())
        throw writeFailure(path, errno);
    row(header);
    m_rows = 0;
}

void CCsvWriter::row(const std::vector<std::string>& cells) {
    if (cells.size() != m_columns)
        throw std::logic_error("CSV row with " + std::to_string(cells.size()) +
                               " cells, header has " + std::to_string(m_columns));
    for (size_t i = 0; i < cells.size(); i++)
        m_out << (i ? "," : "") << quote(cells[i]);
    m_out << "\n";
    m_rows++;
}

void CCsvWriter::close() {
    m_out.flush();
    const int err = errno;
    m_out.close();
    if (!m_out)
        throw writeFailure(m_path, err);
}

// No value (an unreachable cost, a blocked route's U) is an empty cell, as
// summary.json's null: never "inf" or "nan" presented as a result.
std::string CCsvWriter::num(double v, int significant) {
    if (!std::isfinite(v))
        return "";
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*g", significant, v);
    return buf;
}

std::string CCsvWriter::fixed(double v, int decimals) {
    if (!std::isfinite(v))
        return "";
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
    return buf;
}

std::string CCsvWriter::quote(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos)
        return s;
    std::string q = "\"";
    for (char c : s)
        q += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace risknav::common
