#include <risknav/common/CPlotImage.h>
#include <risknav/common/image_file.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace risknav::common {
namespace {
const cv::Scalar kBlack(0, 0, 0), kGrid(225, 225, 225), kWhite(255, 255, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

std::string label(double v) {
    char b[32];
    if (v != 0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e5))
        std::snprintf(b, sizeof(b), "%.0e", v);
    else
        std::snprintf(b, sizeof(b), "%g", v);
    return b;
}
}  // namespace

void CPlotImage::addSeries(const std::string& l, const std::vector<double>& x,
                           const std::vector<double>& y, TRgb c, int t, bool dashed) {
    m_series.push_back({l, x, y, c, t, dashed});
}

void CPlotImage::addVLine(double x, const std::string& l, TRgb c) {
    m_vlines.push_back({x, l, c});
}

std::vector<double> CPlotImage::niceTicks(double lo, double hi, int count) {
    std::vector<double> t;
    if (!(hi > lo))
        return {lo};
    const double raw = (hi - lo) / std::max(1, count);
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    double step = p;
    for (double f : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (f * p >= raw) {
            step = f * p;
            break;
        }
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
        t.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
    return t;
}

cv::Mat CPlotImage::render() const {
    cv::Mat img(m_h, m_w, CV_8UC3, kWhite);
    const int left = 80, right = 20, top = 40,
              bottom = 60 + 20 * int((m_series.size() + 3) / 4);
    const cv::Rect area(left, top, m_w - left - right, m_h - top - bottom);
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    auto ty = [&](double v) { return m_logY ? std::log10(v) : v; };
    for (const auto& s : m_series)
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); i++) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) ||
                (m_logY && s.y[i] <= 0))
                continue;
            x0 = std::min(x0, s.x[i]);
            x1 = std::max(x1, s.x[i]);
            y0 = std::min(y0, ty(s.y[i]));
            y1 = std::max(y1, ty(s.y[i]));
        }
    if (!std::isfinite(x0))
        x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    if (x1 <= x0)
        x1 = x0 + 1;
    if (m_logY) {
        y0 = std::floor(y0);
        y1 = std::max(y0 + 1, std::ceil(y1));
    } else {
        y0 = std::min(0.0, y0);
        if (y1 <= y0)
            y1 = y0 + 1;
        y1 += 0.05 * (y1 - y0);
    }
    auto px = [&](double x) { return area.x + (x - x0) / (x1 - x0) * area.width; };
    auto py = [&](double y) {
        return area.y + area.height - (y - y0) / (y1 - y0) * area.height;
    };

    // Grid and ticks.
    for (double t : niceTicks(x0, x1, 10)) {
        const int X = int(std::lround(px(t)));
        cv::line(img, {X, area.y}, {X, area.y + area.height}, kGrid, 1);
        cv::putText(img, label(t), {X - 12, area.y + area.height + 18}, kFont, 0.42,
                    kBlack, 1, cv::LINE_AA);
    }
    std::vector<double> yt;
    if (m_logY)
        for (double d = y0; d <= y1 + 1e-9; d += 1)
            yt.push_back(d);
    else
        yt = niceTicks(y0, y1, 6);
    for (double t : yt) {
        const int Y = int(std::lround(py(t)));
        cv::line(img, {area.x, Y}, {area.x + area.width, Y}, kGrid, 1);
        const std::string l = m_logY ? label(std::pow(10.0, t)) : label(t);
        cv::putText(img, l, {area.x - 8 - 9 * int(l.size()), Y + 5}, kFont, 0.42, kBlack,
                    1, cv::LINE_AA);
    }
    cv::rectangle(img, area, kBlack, 1);

    for (const auto& v : m_vlines) {
        if (v.x < x0 || v.x > x1)
            continue;
        const int X = int(std::lround(px(v.x)));
        for (int y = area.y; y < area.y + area.height; y += 10)
            cv::line(img, {X, y}, {X, std::min(y + 5, area.y + area.height)}, v.c.bgr(),
                     1, cv::LINE_AA);
        cv::putText(img, v.label, {X + 3, area.y + 14}, kFont, 0.42, v.c.bgr(), 1,
                    cv::LINE_AA);
    }
    for (const auto& s : m_series) {
        cv::Point prev;
        bool have = false;
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); i++) {
            double yv = s.y[i];
            if (!std::isfinite(yv))
                yv = m_logY ? std::pow(10.0, y1) : y1;
            const double yy = (m_logY && yv <= 0) ? y0 : ty(yv);
            const cv::Point p(int(std::lround(px(s.x[i]))),
                              int(std::lround(std::clamp(py(yy), double(area.y),
                                                         double(area.y + area.height)))));
            if (have && (!s.dashed || (i / 4) % 2 == 0))
                cv::line(img, prev, p, s.c.bgr(), s.t, cv::LINE_AA);
            prev = p;
            have = true;
        }
    }
    cv::putText(img, m_title, {left, 26}, kFont, 0.6, kBlack, 1, cv::LINE_AA);
    cv::putText(
        img, m_xlabel,
        {area.x + area.width / 2 - 4 * int(m_xlabel.size()), area.y + area.height + 40},
        kFont, 0.48, kBlack, 1, cv::LINE_AA);
    // Rotated y label.
    {
        int base = 0;
        const cv::Size sz = cv::getTextSize(m_ylabel, kFont, 0.48, 1, &base);
        cv::Mat t(sz.height + base + 4, sz.width + 4, CV_8UC3, kWhite);
        cv::putText(t, m_ylabel, {2, sz.height + 1}, kFont, 0.48, kBlack, 1, cv::LINE_AA);
        cv::Mat r;
        cv::rotate(t, r, cv::ROTATE_90_COUNTERCLOCKWISE);
        const int yPos = std::max(0, area.y + area.height / 2 - r.rows / 2);
        if (r.rows + yPos <= img.rows && r.cols + 4 <= left)
            r.copyTo(img(cv::Rect(4, yPos, r.cols, r.rows)));
    }
    // Legend under the axis label, entries flowing by their text width.
    {
        int lx = left, ly = area.y + area.height + 62;
        for (const auto& se : m_series) {
            if (se.label.empty())
                continue;  // a continuation of a labelled series
            int base = 0;
            const int w =
                34 + cv::getTextSize(se.label, kFont, 0.42, 1, &base).width + 24;
            if (lx + w > m_w - right && lx > left) {
                lx = left;
                ly += 20;
            }
            cv::line(img, {lx, ly - 4}, {lx + 28, ly - 4}, se.c.bgr(), se.t, cv::LINE_AA);
            cv::putText(img, se.label, {lx + 34, ly}, kFont, 0.42, kBlack, 1,
                        cv::LINE_AA);
            lx += w;
        }
    }
    return img;
}

void CPlotImage::save(const std::string& path) const {
    writeImageFile(path, render());
}

}  // namespace risknav::common
