#pragma once
#include <fstream>
#include <string>
#include <vector>

namespace risknav::common {
/** A CSV table with a header row (RFC 4180 quoting). Write it to a path
 * staged by COutputDir so that it appears only when the run succeeds. */
class CCsvWriter {
  public:
    CCsvWriter(const std::string& path, const std::vector<std::string>& header);
    void row(const std::vector<std::string>& cells);
    /** Closes and throws std::runtime_error if anything failed to write. */
    void close();
    size_t rows() const { return m_rows; }

    /** Shortest text that reads back to the same double ("%.9g"); "nan"
     * never appears in our tables, callers decide what a missing value is. */
    static std::string num(double v, int significant = 9);
    /** Fixed-point text, e.g. times: fixed(1600000012.2, 3) = "1600000012.200". */
    static std::string fixed(double v, int decimals);
    static std::string quote(const std::string& s);

  private:
    std::string m_path;
    std::ofstream m_out;
    size_t m_columns, m_rows = 0;
};

}  // namespace risknav::common
