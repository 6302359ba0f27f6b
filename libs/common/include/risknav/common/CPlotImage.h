#pragma once
#include <risknav/common/CMapImage.h>

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace risknav::common {
/** A line chart for people: axes with round-number ticks (or decades on a
 * log scale), axis labels with units, a title, a legend, series as
 * anti-aliased polylines, vertical marker lines with labels. OpenCV only. */
class CPlotImage {
  public:
    CPlotImage(int width = 1100, int height = 520) : m_w(width), m_h(height) {}
    void setTitle(const std::string& t) { m_title = t; }
    void setXLabel(const std::string& l) { m_xlabel = l; }
    void setYLabel(const std::string& l) { m_ylabel = l; }
    /** Log-scale y: non-positive values are drawn at the bottom of the axis. */
    void setLogY(bool on) { m_logY = on; }
    /** A series; an empty label keeps it out of the legend (e.g. further
     * segments of a series drawn in pieces). */
    void addSeries(const std::string& label, const std::vector<double>& x,
                   const std::vector<double>& y, TRgb colour, int thickness = 2,
                   bool dashed = false);
    /** A vertical line at x (e.g. a sensing point), labelled at the top. */
    void addVLine(double x, const std::string& label, TRgb colour);
    cv::Mat render() const;
    void save(const std::string& path) const;

    /** Round tick positions covering [lo, hi] (about `count` of them). */
    static std::vector<double> niceTicks(double lo, double hi, int count);

  private:
    struct TSeries {
        std::string label;
        std::vector<double> x, y;
        TRgb c;
        int t;
        bool dashed;
    };
    struct TVLine {
        double x;
        std::string label;
        TRgb c;
    };
    int m_w, m_h;
    std::string m_title, m_xlabel, m_ylabel;
    bool m_logY = false;
    std::vector<TSeries> m_series;
    std::vector<TVLine> m_vlines;
};

}  // namespace risknav::common
