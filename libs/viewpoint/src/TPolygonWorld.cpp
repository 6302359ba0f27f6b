#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/viewpoint/TPolygonWorld.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

using mrpt::math::TPoint2D;
using risknav::common::CBadInputError;

namespace risknav::viewpoint {
namespace {
using TRing = std::vector<TPoint2D>;

// Outer rings counter-clockwise, holes clockwise: the obstacle on the left.
TRing oriented(TRing r, bool ccw) {
    if ((geometry::signedArea(r) > 0) != ccw)
        std::reverse(r.begin(), r.end());
    return r;
}

TRing boundsRing(const TPolygonWorld& w) {
    // Clockwise: the outside of the rectangle (the walls) on the left.
    return {{w.xMin, w.yMin}, {w.xMin, w.yMax}, {w.xMax, w.yMax}, {w.xMax, w.yMin}};
}

bool inside(const TObstacle& o, const TPoint2D& p) {
    if (!geometry::pointInRing(o.outer, p))
        return false;
    for (const auto& h : o.holes)
        if (geometry::pointInRing(h, p))
            return false;
    return true;
}

[[noreturn]] void fail(const std::string& where, size_t line, const std::string& msg) {
    throw CBadInputError(where + ":" + std::to_string(line) + ": " + msg);
}
}  // namespace

std::vector<TRing> TPolygonWorld::rings() const {
    std::vector<TRing> out;
    for (const auto& o : obstacles) {
        out.push_back(o.outer);
        for (const auto& h : o.holes)
            out.push_back(h);
    }
    if (xMax > xMin && yMax > yMin)
        out.push_back(boundsRing(*this));
    return out;
}

std::vector<geometry::TSegment> TPolygonWorld::edges() const {
    std::vector<geometry::TSegment> e;
    for (const auto& r : rings())
        for (size_t i = 0; i < r.size(); i++)
            e.push_back({r[i], r[(i + 1) % r.size()]});
    return e;
}

bool TPolygonWorld::insideObstacle(const TPoint2D& p) const {
    if (!(p.x > xMin && p.x < xMax && p.y > yMin && p.y < yMax))
        return true;
    for (const auto& o : obstacles)
        if (inside(o, p))
            return true;
    return false;
}

std::vector<TPoint2D> TPolygonWorld::obstacleReferencePoints() const {
    std::vector<TPoint2D> refs;
    for (const auto& o : obstacles) {
        // The vertex centroid when it is inside; otherwise a point just left
        // of (inside) an edge's midpoint, the edge's own scale apart.
        TPoint2D c{0, 0};
        for (const auto& p : o.outer) {
            c.x += p.x / double(o.outer.size());
            c.y += p.y / double(o.outer.size());
        }
        if (!inside(o, c)) {
            for (size_t i = 0; i < o.outer.size(); i++) {
                const auto& a = o.outer[i];
                const auto& b = o.outer[(i + 1) % o.outer.size()];
                const double L = std::hypot(b.x - a.x, b.y - a.y);
                const double eps = 1e-4 * L;
                const TPoint2D q{(a.x + b.x) / 2 - eps * (b.y - a.y) / L,
                                 (a.y + b.y) / 2 + eps * (b.x - a.x) / L};
                if (inside(o, q)) {
                    c = q;
                    break;
                }
            }
        }
        refs.push_back(c);
    }
    return refs;
}

TPolygonWorld parsePolygonWorld(const std::string& text, const std::string& where,
                                bool requireBounds) {
    TPolygonWorld w;
    bool haveBounds = false;
    size_t vertices = 0;
    // A UTF-8 byte order mark (editors add one) is not part of the first line.
    std::istringstream in(text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? text.substr(3)
                                                                  : text);
    std::string line;
    size_t lineNo = 0;
    while (std::getline(in, line)) {
        lineNo++;
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.resize(hash);
        std::istringstream ls(line);
        std::vector<std::string> tok;
        for (std::string t; ls >> t;)
            tok.push_back(t);
        if (tok.empty())
            continue;
        const std::string& kw = tok[0];
        auto number = [&](size_t i, const char* what, const char* unit = "m") {
            double v = 0;
            if (i >= tok.size())
                fail(where, lineNo, kw + ": missing " + what);
            if (!common::parseNumber(tok[i], v))
                fail(where, lineNo,
                     kw + ": " + what + " '" + tok[i] + "' is not a decimal number");
            if (std::abs(v) > TWorldLimits::kMaxCoordinate)
                fail(where, lineNo,
                     kw + ": " + what + " '" + tok[i] + "' is beyond +-1e5 " + unit);
            return v;
        };
        if (kw == "bounds") {
            if (haveBounds)
                fail(where, lineNo, "bounds given twice");
            if (tok.size() != 5)
                fail(where, lineNo, "bounds: expected 'bounds XMIN YMIN XMAX YMAX'");
            w.xMin = number(1, "XMIN");
            w.yMin = number(2, "YMIN");
            w.xMax = number(3, "XMAX");
            w.yMax = number(4, "YMAX");
            if (!(w.xMax > w.xMin && w.yMax > w.yMin))
                fail(where, lineNo, "bounds: XMAX must be > XMIN and YMAX > YMIN");
            haveBounds = true;
        } else if (kw == "obstacle" || kw == "hole") {
            if ((tok.size() - 1) % 2 != 0)
                fail(where, lineNo, kw + ": an odd number of coordinates (x y pairs)");
            if (tok.size() < 7)
                fail(where, lineNo, kw + ": a polygon needs >= 3 vertices");
            if ((tok.size() - 1) / 2 > TWorldLimits::kMaxRingVertices)
                fail(where, lineNo, kw + ": more than 10000 vertices in one polygon");
            vertices += (tok.size() - 1) / 2;
            if (vertices > TWorldLimits::kMaxVertices)
                fail(where, lineNo, "more than 100000 polygon vertices in all");
            TRing r;
            for (size_t i = 1; i < tok.size(); i += 2)
                r.push_back({number(i, "x"), number(i + 1, "y")});
            if (!geometry::ringIsSimple(r))
                fail(where, lineNo,
                     kw + ": the polygon is not simple (edges cross, repeat a vertex or "
                          "fold back)");
            if (std::abs(geometry::signedArea(r)) <= 1e-12)
                fail(where, lineNo, kw + ": the polygon has no area");
            if (kw == "obstacle") {
                w.obstacles.push_back({oriented(r, true), {}, lineNo});
            } else {
                if (w.obstacles.empty())
                    fail(where, lineNo, "hole: no obstacle before it");
                auto& o = w.obstacles.back();
                for (const auto& p : r)
                    if (!geometry::pointInRing(o.outer, p))
                        fail(where, lineNo, "hole: a vertex lies outside its obstacle");
                o.holes.push_back(oriented(r, false));
            }
        } else if (kw == "landmark") {
            if (tok.size() != 5 && tok.size() != 6)
                fail(where, lineNo,
                     "landmark: expected 'landmark ID X Y FACING_DEG [RADIUS]'");
            if (w.landmarks.size() >= TWorldLimits::kMaxLandmarks)
                fail(where, lineNo, "more than 2000 landmarks");
            TLandmark l;
            l.id = tok[1];
            l.line = lineNo;
            if (l.id.size() > TWorldLimits::kMaxIdLength ||
                l.id.find_first_not_of(
                    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                    "0123456789_.:-") != std::string::npos)
                fail(where, lineNo,
                     "landmark: ID '" + l.id.substr(0, 64) +
                         (l.id.size() > 64 ? "..." : "") +
                         "' must be 1 to 64 of A-Z a-z 0-9 _ . : -");
            l.x = number(2, "X");
            l.y = number(3, "Y");
            l.facing = number(4, "FACING_DEG", "deg") * M_PI / 180.0;
            if (tok.size() == 6) {
                l.radius = number(5, "RADIUS");
                if (!(l.radius > 0 && l.radius <= 10))
                    fail(where, lineNo, "landmark: RADIUS must be in (0, 10] m");
            }
            w.landmarks.push_back(l);
        } else
            fail(
                where, lineNo,
                "unknown keyword '" + kw + "' (known: bounds, obstacle, hole, landmark)");
    }
    if (requireBounds && !haveBounds)
        throw CBadInputError(where + ": no 'bounds XMIN YMIN XMAX YMAX' line");
    return w;
}

TPolygonWorld loadPolygonWorld(const std::string& path, bool requireBounds) {
    std::ifstream f(path, std::ios::binary);
    if (!f)
        throw CBadInputError(path + ": cannot open the polygon world file");
    // Bounded read: a world file is text of at most a few MB.
    constexpr size_t kMaxBytes = 64u << 20;
    std::string text;
    char buf[65536];
    while (f.read(buf, sizeof(buf)) || f.gcount() > 0) {
        text.append(buf, size_t(f.gcount()));
        if (text.size() > kMaxBytes)
            throw CBadInputError(path + ": larger than 64 MiB; not a polygon world file");
    }
    if (text.find('\0') != std::string::npos)
        throw CBadInputError(path + ": binary data; not a polygon world text file");
    return parsePolygonWorld(text, path, requireBounds);
}

void validateWorld(const TPolygonWorld& w, const std::string& where) {
    if (!(w.xMax > w.xMin && w.yMax > w.yMin))
        throw CBadInputError(where + ": the world has no bounds (outer walls)");
    auto inBounds = [&](const TPoint2D& p) {
        return p.x >= w.xMin && p.x <= w.xMax && p.y >= w.yMin && p.y <= w.yMax;
    };
    for (size_t i = 0; i < w.obstacles.size(); i++) {
        const auto& o = w.obstacles[i];
        const std::string name = o.line
                                     ? where + ":" + std::to_string(o.line) + ": obstacle"
                                     : where + ": obstacle " + std::to_string(i + 1);
        if (!geometry::ringIsSimple(o.outer))
            throw CBadInputError(name + " is not a simple polygon");
        for (const auto& p : o.outer)
            if (!inBounds(p))
                throw CBadInputError(name + " reaches outside the bounds");
        for (const auto& h : o.holes) {
            if (!geometry::ringIsSimple(h))
                throw CBadInputError(name + ": a hole is not a simple polygon");
            for (const auto& p : h)
                if (!geometry::pointInRing(o.outer, p))
                    throw CBadInputError(name + ": a hole reaches outside it");
        }
    }
    std::set<std::string> ids;
    for (const auto& l : w.landmarks) {
        const std::string at =
            l.line ? where + ":" + std::to_string(l.line) + ": landmark '" + l.id + "'"
                   : where + ": landmark '" + l.id + "'";
        if (!ids.insert(l.id).second)
            throw CBadInputError(at + ": the id is given twice");
        const TPoint2D front{l.x + 1e-3 * std::cos(l.facing),
                             l.y + 1e-3 * std::sin(l.facing)};
        if (!inBounds({l.x, l.y}))
            throw CBadInputError(at + " lies outside the bounds");
        if (w.insideObstacle(front))
            throw CBadInputError(at + " lies inside an obstacle or faces into its wall");
    }
}

size_t snapLandmarksToWalls(TPolygonWorld& w, double tolerance) {
    const auto edges = w.edges();
    size_t moved = 0;
    for (auto& l : w.landmarks) {
        const TPoint2D front{l.x + 1e-3 * std::cos(l.facing),
                             l.y + 1e-3 * std::sin(l.facing)};
        if (!w.insideObstacle(front))
            continue;
        double best = tolerance;
        TPoint2D to{l.x, l.y};
        for (const auto& e : edges) {
            const double vx = e.b.x - e.a.x, vy = e.b.y - e.a.y, L2 = vx * vx + vy * vy;
            const double t =
                L2 > 0
                    ? std::clamp(((l.x - e.a.x) * vx + (l.y - e.a.y) * vy) / L2, 0.0, 1.0)
                    : 0;
            const TPoint2D q{e.a.x + t * vx, e.a.y + t * vy};
            const double d = std::hypot(q.x - l.x, q.y - l.y);
            // Onto an edge whose outside the landmark faces.
            const double outx = vy,
                         outy = -vx;  // right of the edge: outside the obstacle
            if (d <= best && outx * std::cos(l.facing) + outy * std::sin(l.facing) > 0) {
                best = d;
                to = q;
            }
        }
        if (to.x != l.x || to.y != l.y) {
            l.x = to.x;
            l.y = to.y;
            moved++;
        }
    }
    return moved;
}

std::vector<TObstacle> obstaclesFromGrid(const mrpt::maps::COccupancyGridMap2D& g,
                                         const mapping::TObstacleRule& rule,
                                         double tolerance) {
    const int nx = int(g.getSizeX()), ny = int(g.getSizeY());
    const double res = g.getResolution();
    // Row 0 of the mask is cell row 0 (min y): no flip, pixel (c, r) = cell (c, r).
    cv::Mat mask(ny, nx, CV_8UC1, cv::Scalar(0));
    for (int r = 0; r < ny; r++)
        for (int c = 0; c < nx; c++)
            if (rule.isObstacle(g.getCell(c, r)))
                mask.at<uint8_t>(r, c) = 255;
    cv::dilate(mask, mask, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
    std::vector<std::vector<cv::Point>> contours;
    std::vector<cv::Vec4i> hierarchy;
    cv::findContours(mask, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
    auto toWorld = [&](const std::vector<cv::Point>& c) {
        std::vector<cv::Point> approx;
        cv::approxPolyDP(c, approx, std::max(0.0, tolerance / res), true);
        TRing r;
        for (const auto& p : approx)
            r.push_back({g.idx2x(p.x), g.idx2y(p.y)});
        return r;
    };
    std::vector<TObstacle> out;
    for (size_t i = 0; i < contours.size(); i++) {
        if (hierarchy[i][3] >= 0)
            continue;  // a hole: added to its parent below
        TRing outer = toWorld(contours[i]);
        if (outer.size() < 3 || !geometry::ringIsSimple(outer) ||
            std::abs(geometry::signedArea(outer)) < 2 * res * res)
            continue;
        TObstacle o{oriented(outer, true), {}};
        for (int h = hierarchy[i][2]; h >= 0; h = hierarchy[h][0]) {
            TRing hole = toWorld(contours[size_t(h)]);
            if (hole.size() >= 3 && geometry::ringIsSimple(hole))
                o.holes.push_back(oriented(hole, false));
        }
        out.push_back(std::move(o));
    }
    return out;
}

}  // namespace risknav::viewpoint
