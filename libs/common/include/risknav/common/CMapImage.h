#pragma once
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/math/TPoint2D.h>

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace risknav::common {
/** An RGB colour (0-255 per channel). */
struct TRgb {
    uint8_t r = 0, g = 0, b = 0;
    cv::Scalar bgr() const { return cv::Scalar(b, g, r); }
};

/** A picture of a map for people: the grid (occupied black, free white,
 * unknown grey) with drawings in world coordinates [m], a title with the key
 * figure, a legend, a scale bar in metres and, when a heat overlay is drawn, a
 * colour bar with units. Built on OpenCV (anti-aliased lines and text,
 * cv::applyColorMap). */
class CMapImage {
  public:
    enum class TMarker { Cross, Plus, Circle, Square, Triangle, Star };

    /** maxSidePx: the map is scaled so its longer side is at most this many
     * pixels (and at least 1 pixel per cell when that fits). */
    explicit CMapImage(const mrpt::maps::COccupancyGridMap2D& grid, int maxSidePx = 1400);

    /** World [m] -> pixel in the map area (sub-pixel). */
    cv::Point2d toPixel(double x, double y) const;
    double pixelsPerMeter() const { return m_pxPerM; }

    void setTitle(const std::string& t) { m_title = t; }

    /** Colour overlay of one value per grid cell (row-major, cx + cy*sizeX).
     * Values below `showFrom` stay transparent; alpha blends with the map.
     * Adds a colour bar "label [units]" from vmin to vmax. */
    void heatOverlay(const std::vector<float>& cellValues, float vmin, float vmax,
                     const std::string& label, double alpha = 0.6,
                     float showFrom = -1e30f, int colormap = 2 /* cv::COLORMAP_JET */);

    /** A colour bar "label [units]" from vmin to vmax for things drawn in
     * colourOf() colours (e.g. a path coloured by speed). */
    void colourBar(float vmin, float vmax, const std::string& label,
                   int colormap = 2 /* cv::COLORMAP_JET */);
    /** The colour of value v on the bar vmin..vmax (clamped). */
    static TRgb colourOf(double v, double vmin, double vmax,
                         int colormap = 2 /* cv::COLORMAP_JET */);

    /** Paints the cells where mask (row-major, one byte per cell) is non-zero. */
    void paintCells(const std::vector<uint8_t>& mask, TRgb c);

    void polyline(const std::vector<mrpt::math::TPoint2D>& pts, TRgb c,
                  int thicknessPx = 2, bool dashed = false);
    void segment(const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b, TRgb c,
                 int thicknessPx = 2);
    /** The nSigma ellipse of a 2x2 position covariance [m^2] around `mean`. */
    void ellipse(const mrpt::math::TPoint2D& mean,
                 const mrpt::math::CMatrixFixed<double, 2, 2>& cov, double nSigma, TRgb c,
                 int thicknessPx = 1);
    void circle(const mrpt::math::TPoint2D& p, double radiusM, TRgb c,
                int thicknessPx = 1, bool filled = false);
    void marker(const mrpt::math::TPoint2D& p, TMarker m, TRgb c, int sizePx = 8,
                int thicknessPx = 2);
    /** Text anchored at a world point (left-baseline), with a light halo. */
    void text(const mrpt::math::TPoint2D& p, const std::string& s, TRgb c,
              double scale = 0.45);

    /** A legend entry: a short line (style Line) or a marker. */
    void legendLine(const std::string& label, TRgb c, int thicknessPx = 2);
    void legendMarker(const std::string& label, TMarker m, TRgb c);

    /** Composes title, map, legend, scale bar and colour bar. */
    cv::Mat compose() const;
    /** compose() and write a PNG; throws std::runtime_error on failure. */
    void save(const std::string& path) const;

    cv::Mat& mapArea() { return m_map; }

    /** A "nice" scale bar length (1, 2 or 5 x 10^k m) close to target metres. */
    static double niceLength(double targetM);

  private:
    struct TLegend {
        std::string label;
        TRgb c;
        bool isMarker;
        TMarker m;
        int thickness;
    };
    struct TColourBar {
        float vmin, vmax;
        std::string label;
        int colormap;
    };
    cv::Mat m_map;  // BGR, the map area only
    double m_xmin, m_ymax, m_pxPerM;
    std::string m_title;
    std::vector<TLegend> m_legend;
    std::vector<TColourBar> m_bars;
    int m_cellsX, m_cellsY;
};

/** A qualitative palette for series (routes, agents): distinct, print-safe. */
TRgb seriesColour(size_t i);

}  // namespace risknav::common
