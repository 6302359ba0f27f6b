#include <risknav/common/CMapImage.h>
#include <risknav/common/image_file.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

using mrpt::math::TPoint2D;

namespace risknav::common {
namespace {
const cv::Scalar kBlack(0, 0, 0), kWhite(255, 255, 255), kGrey(90, 90, 90);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

std::string shortNum(double v) {
    char b[32];
    if (v != 0 && (std::abs(v) < 0.01 || std::abs(v) >= 1e4))
        std::snprintf(b, sizeof(b), "%.2g", v);
    else
        std::snprintf(b, sizeof(b), "%.3g", v);
    return b;
}
}  // namespace

TRgb seriesColour(size_t i) {
    static const TRgb pal[] = {{0, 114, 178},   {213, 94, 0},   {0, 158, 115},
                               {204, 121, 167}, {230, 159, 0},  {86, 180, 233},
                               {120, 60, 20},   {100, 100, 100}};
    return pal[i % (sizeof(pal) / sizeof(pal[0]))];
}

CMapImage::CMapImage(const mrpt::maps::COccupancyGridMap2D& g, int maxSidePx) {
    m_cellsX = static_cast<int>(g.getSizeX());
    m_cellsY = static_cast<int>(g.getSizeY());
    const double res = g.getResolution();
    const int longest = std::max(m_cellsX, m_cellsY);
    // Integer zoom when the map is small (crisp cells), fractional shrink when large.
    double pxPerCell = longest <= maxSidePx ? std::max(1, maxSidePx / longest)
                                            : double(maxSidePx) / longest;
    pxPerCell = std::min(pxPerCell, 8.0);
    m_pxPerM = pxPerCell / res;
    m_xmin = g.getXMin();
    m_ymax = g.getYMax();
    cv::Mat cells(m_cellsY, m_cellsX, CV_8UC1);
    for (int cy = 0; cy < m_cellsY; cy++) {
        uint8_t* row = cells.ptr<uint8_t>(m_cellsY - 1 - cy);
        for (int cx = 0; cx < m_cellsX; cx++)
            row[cx] = static_cast<uint8_t>(std::lround(255.0 * g.getCell(cx, cy)));
    }
    cv::Mat grey;
    const cv::Size sz(std::max(1, int(std::lround(m_cellsX * pxPerCell))),
                      std::max(1, int(std::lround(m_cellsY * pxPerCell))));
    cv::resize(cells, grey, sz, 0, 0,
               pxPerCell >= 1 ? cv::INTER_NEAREST : cv::INTER_AREA);
    cv::cvtColor(grey, m_map, cv::COLOR_GRAY2BGR);
}

cv::Point2d CMapImage::toPixel(double x, double y) const {
    return {(x - m_xmin) * m_pxPerM, (m_ymax - y) * m_pxPerM};
}

void CMapImage::heatOverlay(const std::vector<float>& v, float vmin, float vmax,
                            const std::string& label, double alpha, float showFrom,
                            int colormap) {
    if (v.size() != size_t(m_cellsX) * m_cellsY)
        throw std::logic_error("heatOverlay: value count does not match the grid");
    if (!(vmax > vmin))
        vmax = vmin + 1.0f;
    cv::Mat norm(m_cellsY, m_cellsX, CV_8UC1), mask(m_cellsY, m_cellsX, CV_8UC1);
    for (int cy = 0; cy < m_cellsY; cy++) {
        uint8_t* n = norm.ptr<uint8_t>(m_cellsY - 1 - cy);
        uint8_t* m = mask.ptr<uint8_t>(m_cellsY - 1 - cy);
        for (int cx = 0; cx < m_cellsX; cx++) {
            const float val = v[size_t(cy) * m_cellsX + cx];
            const bool show = std::isfinite(val) && val >= showFrom;
            m[cx] = show ? 255 : 0;
            const double t = std::clamp((val - vmin) / double(vmax - vmin), 0.0, 1.0);
            n[cx] = show ? static_cast<uint8_t>(std::lround(255 * t)) : 0;
        }
    }
    cv::Mat colour, bigColour, bigMask;
    cv::applyColorMap(norm, colour, colormap);
    cv::resize(colour, bigColour, m_map.size(), 0, 0, cv::INTER_NEAREST);
    cv::resize(mask, bigMask, m_map.size(), 0, 0, cv::INTER_NEAREST);
    cv::Mat blended;
    cv::addWeighted(m_map, 1.0 - alpha, bigColour, alpha, 0.0, blended);
    blended.copyTo(m_map, bigMask);
    m_bars.push_back({vmin, vmax, label, colormap});
}

void CMapImage::colourBar(float vmin, float vmax, const std::string& label,
                          int colormap) {
    m_bars.push_back({vmin, vmax > vmin ? vmax : vmin + 1.0f, label, colormap});
}

TRgb CMapImage::colourOf(double v, double vmin, double vmax, int colormap) {
    const double t = vmax > vmin && std::isfinite(v)
                         ? std::clamp((v - vmin) / (vmax - vmin), 0.0, 1.0)
                         : 0.0;
    cv::Mat one(1, 1, CV_8UC1, cv::Scalar(std::lround(255 * t))), col;
    cv::applyColorMap(one, col, colormap);
    const auto p = col.at<cv::Vec3b>(0, 0);
    return TRgb{p[2], p[1], p[0]};
}

void CMapImage::paintCells(const std::vector<uint8_t>& mask, TRgb c) {
    if (mask.size() != size_t(m_cellsX) * m_cellsY)
        throw std::logic_error("paintCells: mask size does not match the grid");
    const double cell =
        m_pxPerM * (m_map.cols / (m_pxPerM * m_cellsX));  // pixels per cell
    for (int cy = 0; cy < m_cellsY; cy++)
        for (int cx = 0; cx < m_cellsX; cx++)
            if (mask[size_t(cy) * m_cellsX + cx]) {
                const int x0 = int(cx * cell), y0 = int((m_cellsY - 1 - cy) * cell);
                cv::rectangle(
                    m_map,
                    cv::Rect(x0, y0, std::max(1, int(cell)), std::max(1, int(cell))),
                    c.bgr(), cv::FILLED);
            }
}

void CMapImage::polyline(const std::vector<TPoint2D>& pts, TRgb c, int t, bool dashed) {
    if (!dashed) {
        for (size_t i = 1; i < pts.size(); i++)
            segment(pts[i - 1], pts[i], c, t);
        return;
    }
    // Dashes follow the arc length in pixels (8 on, 6 off), across vertices.
    const double on = 8.0, period = 14.0;
    double phase = 0.0;
    for (size_t i = 1; i < pts.size(); i++) {
        const double lenPx =
            std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y) * m_pxPerM;
        double s = 0.0;
        while (s < lenPx) {
            const double inPeriod = std::fmod(phase + s, period);
            const double runEnd =
                std::min(lenPx, s + (inPeriod < on ? on - inPeriod : period - inPeriod));
            if (inPeriod < on && lenPx > 0) {
                const double f0 = s / lenPx, f1 = runEnd / lenPx;
                segment({pts[i - 1].x + f0 * (pts[i].x - pts[i - 1].x),
                         pts[i - 1].y + f0 * (pts[i].y - pts[i - 1].y)},
                        {pts[i - 1].x + f1 * (pts[i].x - pts[i - 1].x),
                         pts[i - 1].y + f1 * (pts[i].y - pts[i - 1].y)},
                        c, t);
            }
            s = runEnd;
        }
        phase = std::fmod(phase + lenPx, period);
    }
}

void CMapImage::segment(const TPoint2D& a, const TPoint2D& b, TRgb c, int t) {
    constexpr int kShift = 4;  // sub-pixel precision for anti-aliased lines
    auto fx = [](const cv::Point2d& p) {
        return cv::Point(int(std::lround(p.x * (1 << kShift))),
                         int(std::lround(p.y * (1 << kShift))));
    };
    cv::line(m_map, fx(toPixel(a.x, a.y)), fx(toPixel(b.x, b.y)), c.bgr(), t, cv::LINE_AA,
             kShift);
}

void CMapImage::ellipse(const TPoint2D& mean,
                        const mrpt::math::CMatrixFixed<double, 2, 2>& cov, double nSigma,
                        TRgb c, int t) {
    // Axes from the eigen-decomposition of the symmetric 2x2 covariance.
    const double a = cov(0, 0), b = cov(0, 1), d = cov(1, 1);
    const double tr = a + d, det = a * d - b * b;
    const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
    const double l1 = std::max(0.0, tr / 2 + disc), l2 = std::max(0.0, tr / 2 - disc);
    const double ang = 0.5 * std::atan2(2 * b, a - d);  // of the major axis, world frame
    const cv::Point2d ctr = toPixel(mean.x, mean.y);
    const cv::Size2d axes(std::max(0.5, nSigma * std::sqrt(l1) * m_pxPerM),
                          std::max(0.5, nSigma * std::sqrt(l2) * m_pxPerM));
    // Image y points down: a world angle is negated.
    cv::ellipse(m_map,
                cv::RotatedRect(ctr, cv::Size2f(2 * axes.width, 2 * axes.height),
                                float(-ang * 180.0 / M_PI)),
                c.bgr(), t, cv::LINE_AA);
}

void CMapImage::circle(const TPoint2D& p, double r, TRgb c, int t, bool filled) {
    const cv::Point2d q = toPixel(p.x, p.y);
    cv::circle(m_map, cv::Point(int(std::lround(q.x)), int(std::lround(q.y))),
               std::max(1, int(std::lround(r * m_pxPerM))), c.bgr(),
               filled ? cv::FILLED : t, cv::LINE_AA);
}

static void drawMarkerAt(cv::Mat& img, cv::Point p, CMapImage::TMarker m,
                         const cv::Scalar& c, int s, int t) {
    using M = CMapImage::TMarker;
    switch (m) {
        case M::Cross:
            cv::drawMarker(img, p, c, cv::MARKER_TILTED_CROSS, s, t, cv::LINE_AA);
            break;
        case M::Plus:
            cv::drawMarker(img, p, c, cv::MARKER_CROSS, s, t, cv::LINE_AA);
            break;
        case M::Circle:
            cv::circle(img, p, std::max(2, s / 2), c, t, cv::LINE_AA);
            break;
        case M::Square:
            cv::drawMarker(img, p, c, cv::MARKER_SQUARE, s, t, cv::LINE_AA);
            break;
        case M::Triangle:
            cv::drawMarker(img, p, c, cv::MARKER_TRIANGLE_UP, s, t, cv::LINE_AA);
            break;
        case M::Star:
            cv::drawMarker(img, p, c, cv::MARKER_STAR, s, t, cv::LINE_AA);
            break;
    }
}

void CMapImage::marker(const TPoint2D& p, TMarker m, TRgb c, int s, int t) {
    const cv::Point2d q = toPixel(p.x, p.y);
    drawMarkerAt(m_map, cv::Point(int(std::lround(q.x)), int(std::lround(q.y))), m,
                 c.bgr(), s, t);
}

void CMapImage::text(const TPoint2D& p, const std::string& s, TRgb c, double scale) {
    const cv::Point2d q = toPixel(p.x, p.y);
    const cv::Point at(int(std::lround(q.x)), int(std::lround(q.y)));
    cv::putText(m_map, s, at, kFont, scale, kWhite, 3, cv::LINE_AA);
    cv::putText(m_map, s, at, kFont, scale, c.bgr(), 1, cv::LINE_AA);
}

void CMapImage::legendLine(const std::string& label, TRgb c, int t) {
    m_legend.push_back({label, c, false, TMarker::Plus, t});
}

void CMapImage::legendMarker(const std::string& label, TMarker m, TRgb c) {
    m_legend.push_back({label, c, true, m, 2});
}

double CMapImage::niceLength(double target) {
    if (!(target > 0))
        return 1.0;
    const double p = std::pow(10.0, std::floor(std::log10(target)));
    for (double f : {5.0, 2.0, 1.0})
        if (f * p <= target)
            return f * p;
    return p;
}

cv::Mat CMapImage::compose() const {
    const int titleH = 34, barW = m_bars.empty() ? 0 : 110 * int(m_bars.size()), pad = 10;
    // Legend flows in rows under the map.
    const int W = std::max(m_map.cols + barW, 520);
    std::vector<cv::Point> legendPos;
    int lx = pad, ly = 0, rows = 1;
    for (const auto& e : m_legend) {
        int base = 0;
        const int w = 40 + cv::getTextSize(e.label, kFont, 0.45, 1, &base).width + 18;
        if (lx + w > W - 220 && lx > pad) {
            lx = pad;
            rows++;
            ly += 22;
        }
        legendPos.emplace_back(lx, ly);
        lx += w;
    }
    const int bottomH = std::max(50, 18 + rows * 22 + 12);
    const int H = titleH + std::max(m_map.rows, m_bars.empty() ? 0 : 200) + bottomH;
    cv::Mat out(H, W, CV_8UC3, kWhite);
    m_map.copyTo(out(cv::Rect(0, titleH, m_map.cols, m_map.rows)));
    cv::rectangle(out, cv::Rect(0, titleH, m_map.cols, m_map.rows), kGrey, 1);
    cv::putText(out, m_title, cv::Point(pad, 24), kFont, 0.6, kBlack, 1, cv::LINE_AA);

    const int y0 = titleH + m_map.rows + 20;
    for (size_t i = 0; i < m_legend.size(); i++) {
        const auto& e = m_legend[i];
        const cv::Point p = legendPos[i] + cv::Point(0, y0);
        if (e.isMarker)
            drawMarkerAt(out, p + cv::Point(14, -4), e.m, e.c.bgr(), 10, 2);
        else
            cv::line(out, p + cv::Point(0, -4), p + cv::Point(30, -4), e.c.bgr(),
                     e.thickness, cv::LINE_AA);
        cv::putText(out, e.label, p + cv::Point(38, 0), kFont, 0.45, kBlack, 1,
                    cv::LINE_AA);
    }
    // Scale bar: about a fifth of the map width, a round number of metres.
    const double len = niceLength(0.2 * m_map.cols / m_pxPerM);
    const int lenPx = int(std::lround(len * m_pxPerM));
    const cv::Point sb(W - pad - lenPx, y0 - 2);
    cv::rectangle(out, cv::Rect(sb.x, sb.y - 5, lenPx, 6), kBlack, cv::FILLED);
    cv::rectangle(out, cv::Rect(sb.x + lenPx / 2, sb.y - 4, lenPx - lenPx / 2 - 1, 4),
                  kWhite, cv::FILLED);
    cv::putText(out, shortNum(len) + " m", sb + cv::Point(0, 18), kFont, 0.45, kBlack, 1,
                cv::LINE_AA);

    for (size_t b = 0; b < m_bars.size(); b++) {
        const auto& bar = m_bars[b];
        const int x = m_map.cols + 14 + 110 * int(b), y = titleH + 24, h = 160, w = 18;
        cv::Mat ramp(h, 1, CV_8UC1);
        for (int i = 0; i < h; i++)
            ramp.at<uint8_t>(i, 0) = static_cast<uint8_t>(255 - (255 * i) / (h - 1));
        cv::Mat col, colW;
        cv::applyColorMap(ramp, col, bar.colormap);
        cv::resize(col, colW, cv::Size(w, h), 0, 0, cv::INTER_NEAREST);
        colW.copyTo(out(cv::Rect(x, y, w, h)));
        cv::rectangle(out, cv::Rect(x, y, w, h), kBlack, 1);
        cv::putText(out, shortNum(bar.vmax), cv::Point(x + w + 4, y + 8), kFont, 0.4,
                    kBlack, 1, cv::LINE_AA);
        cv::putText(out, shortNum(0.5 * (bar.vmin + bar.vmax)),
                    cv::Point(x + w + 4, y + h / 2 + 4), kFont, 0.4, kBlack, 1,
                    cv::LINE_AA);
        cv::putText(out, shortNum(bar.vmin), cv::Point(x + w + 4, y + h), kFont, 0.4,
                    kBlack, 1, cv::LINE_AA);
        cv::putText(out, bar.label, cv::Point(x - 4, y - 8), kFont, 0.4, kBlack, 1,
                    cv::LINE_AA);
    }
    return out;
}

void CMapImage::save(const std::string& path) const {
    writeImageFile(path, compose(), {cv::IMWRITE_PNG_COMPRESSION, 6});
}

}  // namespace risknav::common
