#include <risknav/common/config_read.h>
#include <risknav/geometry/homotopy.h>
#include <risknav/geometry/polyline.h>
#include <risknav/mapping/distance_transform.h>
#include <risknav/planning/CGlobalPlanner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;

namespace risknav::planning {
namespace {
/** map = built: a way within a cell of the sensed points is taken when the
 * one that keeps the whole disc off them is longer than this times it
 * (+ 1 m). */
constexpr double kDetourRatio = 1.5;
constexpr float kInf = std::numeric_limits<float>::infinity();
/** [s] a cell sensed as an obstacle is not forgotten by a beam through it
 * sooner than this after. */
constexpr float kForgetGrace = 2.0f;
std::string metres(double v) {
    char b[32];
    std::snprintf(b, sizeof(b), "%.3f m", v);
    return b;
}
}  // namespace

void CGlobalPlanner::TOptions::declare(Visitor& v) {
    v.number(margin, "margin", TRange::closed(0, 2, "m"),
             "a way keeps this beyond the engine's disc");
    v.number(clearance_soft, "clearance_soft", TRange::closed(0, 10, "m"),
             "beyond the disc, nearer costs more");
    v.number(clearance_weight, "clearance_weight", TRange::closed(0, 1000),
             "a metre at the disc's edge costs 1 + this");
    v.number(lookahead, "lookahead", TRange::closed(0.2, 20, "m"),
             "MRPT's engine aims this far ahead on the plan");
    v.number(stray_distance, "stray_distance", TRange::closed(0.1, 100, "m"),
             "this far from the plan: replan");
    v.number(pose_jump, "pose_jump", TRange::closed(0.05, 100, "m"),
             "the pose moved this far in one cycle: replan");
    v.number(check_ahead, "check_ahead", TRange::closed(0, 100, "m"),
             "of the plan checked for sensed obstacles");
    v.number(obstacle_memory, "obstacle_memory", TRange::closed(0, 3600, "s"),
             "a sensed obstacle not on the map is kept");
    v.number(replan_interval, "replan_interval", TRange::closed(0, 3600, "s"),
             "at least between replans for blocking");
    v.integer(candidates, "candidates", TRange::closed(1, 8),
              "global_planner = risk: ways of distinct classes scored");
    v.choice(map, "map", {"known", "built"},
             "the world's map, or its extent only (free until sensed)");
}

float CGlobalPlanner::costOf(double e) const {
    if (!(e >= m_disc))
        return kInf;
    const double soft = options.clearance_soft;
    if (!(soft > 0) || e >= m_disc + soft)
        return 1.0f;
    const double f = (m_disc + soft - e) / soft;
    return float(1.0 + options.clearance_weight * f * f);
}

void CGlobalPlanner::setMap(const mrpt::maps::COccupancyGridMap2D& grid,
                            const mapping::TObstacleRule& rule, double discRadius) {
    m_field = mapping::CDistanceField(grid, rule);
    m_disc = discRadius + options.margin;
    m_fine.cost.w = m_field.sizeX();
    m_fine.cost.h = m_field.sizeY();
    m_fine.cost.resolution = m_field.resolution();
    const auto& d = m_field.clearances();
    const size_t n = d.size();
    const float half = float(0.5 * m_fine.cost.resolution);
    m_fine.clearEdge.resize(n);
    m_fine.cost.cost.resize(n);
    for (size_t i = 0; i < n; i++) {
        // the centre's distance to the nearest obstacle cell's centre, less
        // half a cell: to that cell's near edge (0 on an obstacle)
        m_fine.clearEdge[i] = m_field.obstacles()[i] ? 0.0f : std::max(0.0f, d[i] - half);
        m_fine.cost.cost[i] = costOf(m_fine.clearEdge[i]);
    }
    m_fine.k = 1;
    // A map finer than 5 cm is planned on cells of k x k of its own (k =
    // 0.05 m / resolution, rounded): a 3 cm map has 2.8 times the cells of
    // a 5 cm one for the same metres, and the engine follows a plan to
    // centimetres no better. A coarse cell keeps the least clearance of its
    // own cells (a gap only that closes is planned on the map's cells).
    m_coarse = TLevel{};
    const int k = int(std::lround(0.05 / m_fine.cost.resolution));
    if (k > 1) {
        auto& L = m_coarse;
        L.k = k;
        L.cost.w = (m_fine.cost.w + k - 1) / k;
        L.cost.h = (m_fine.cost.h + k - 1) / k;
        L.cost.resolution = k * m_fine.cost.resolution;
        L.clearEdge.assign(size_t(L.cost.w) * size_t(L.cost.h), kInf);
        for (int y = 0; y < m_fine.cost.h; y++)
            for (int x = 0; x < m_fine.cost.w; x++) {
                float& e = L.clearEdge[L.cost.index(x / k, y / k)];
                e = std::min(e, m_fine.clearEdge[m_fine.cost.index(x, y)]);
            }
        L.cost.cost.resize(L.clearEdge.size());
        for (size_t i = 0; i < L.clearEdge.size(); i++)
            L.cost.cost[i] = costOf(L.clearEdge[i]);
    }
    m_seenAt.resize(n);
    m_keepSeen = options.map == "built";
    resetFollowing();
}

void CGlobalPlanner::resetFollowing() {
    // a new run starts its own clock: the last run's sensed cells would
    // otherwise count as seen a moment ago
    std::fill(m_seenAt.begin(), m_seenAt.end(), kNeverSeen);
    m_timeBase.reset();
    m_seenCells.clear();
    m_target.reset();
    m_lastPose.reset();
    m_plan = TGlobalPlan{};
    m_planSlack = 0;
    m_events.clear();
    m_choices.clear();
    m_lastBlockedReplan = -1e18;
    m_progress = 0;
}

TGlobalPlan CGlobalPlanner::plan(const TPoint2D& from, const TPoint2D& to,
                                 bool withSensed) const {
    const auto t0 = std::chrono::steady_clock::now();
    TGlobalPlan p;
    auto done = [&] {
        p.ms =
            1e3 *
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return p;
    };
    if (!hasMap()) {
        p.failure = "start_blocked";
        p.reason = "no map to plan on";
        return done();
    }
    const int sx = m_field.x2idx(from.x), sy = m_field.y2idx(from.y);
    const int gx = m_field.x2idx(to.x), gy = m_field.y2idx(to.y);
    if (!m_fine.cost.inside(sx, sy)) {
        p.failure = "start_blocked";
        p.reason = "the start " + pointText(from.x, from.y) + " is outside the map";
        return done();
    }
    if (!m_fine.cost.inside(gx, gy)) {
        p.failure = "goal_blocked";
        p.reason = "the goal " + pointText(to.x, to.y) + " is outside the map";
        return done();
    }
    const int32_t si = int32_t(m_fine.cost.index(sx, sy)),
                  gi = int32_t(m_fine.cost.index(gx, gy));
    if (m_fine.clearEdge[size_t(si)] <= 0) {
        p.failure = "start_blocked";
        p.reason = "the start " + pointText(from.x, from.y) +
                   " is on an obstacle cell of the map";
        return done();
    }
    if (m_fine.clearEdge[size_t(gi)] <= 0) {
        p.failure = "goal_blocked";
        p.reason =
            "the goal " + pointText(to.x, to.y) + " is on an obstacle cell of the map";
        return done();
    }
    // on the coarse level first (a map finer than 5 cm), then on the map's
    // own cells: a gap the coarse cells' least clearance closes
    bool found = m_coarse.k > 1 && planOn(m_coarse, from, to, withSensed, p);
    if (!found)
        found = planOn(m_fine, from, to, withSensed, p);
    if (!found) {
        const double widest =
            widestWayClearance(m_fine.clearEdge, m_fine.cost.w, m_fine.cost.h, si, gi);
        if (!(widest > 0)) {
            p.failure = "disconnected";
            p.reason = "no way on the map's free space joins " +
                       pointText(from.x, from.y) + " and " + pointText(to.x, to.y);
        } else if (widest < m_disc) {
            p.failure = "narrow_gap";
            p.reason = "the widest way from " + pointText(from.x, from.y) + " to " +
                       pointText(to.x, to.y) + " passes " + metres(widest) +
                       " from an obstacle, a gap of about " + metres(2 * widest) +
                       "; the robot's disc needs " + metres(m_disc) +
                       " (radius + shape_margin + margin)";
        } else {
            p.failure = "blocked";
            p.reason = "the sensed obstacles block every way from " +
                       pointText(from.x, from.y) + " to " + pointText(to.x, to.y);
        }
    }
    return done();
}

void CGlobalPlanner::sensedClearance(const TLevel& L, std::vector<float>& out) const {
    const int fw = m_fine.cost.w, fh = m_fine.cost.h, k = L.k;
    const double fres = m_fine.cost.resolution;
    const double reachM = m_disc + options.clearance_soft;
    const int reach = int(std::ceil(reachM / fres)) + 1;
    out.assign(L.cost.cost.size(), kInf);
    size_t live = 0;
    for (const int32_t c : m_seenCells)
        live += liveSeen(size_t(c), m_now);
    if (live == 0)
        return;
    auto take = [&](int x, int y, double d) {
        const double e = std::max(0.0, d - 0.5 * fres) + m_sensedSlack;
        if (e > reachM)
            return;
        float& o = out[L.cost.index(x / k, y / k)];
        o = std::min(o, float(e));
    };
    const size_t stamp = size_t(2 * reach + 1) * size_t(2 * reach + 1);
    if (live * stamp < size_t(fw) * size_t(fh)) {
        // a few (people, clutter): the disc about each
        for (const int32_t c : m_seenCells) {
            if (!liveSeen(size_t(c), m_now))
                continue;
            const int cx = c % fw, cy = c / fw;
            for (int dy = -reach; dy <= reach; dy++)
                for (int dx = -reach; dx <= reach; dx++)
                    if (m_fine.cost.inside(cx + dx, cy + dy))
                        take(cx + dx, cy + dy, std::hypot(dx, dy) * fres);
        }
        return;
    }
    // many (map = built: every wall seen): one exact distance transform
    m_sensedMask.assign(size_t(fw) * size_t(fh), 0);
    for (const int32_t c : m_seenCells)
        if (liveSeen(size_t(c), m_now))
            m_sensedMask[size_t(c)] = 1;
    mapping::squaredDistanceTransform(m_sensedMask, fw, fh, false, m_sensedD2);
    for (int y = 0; y < fh; y++)
        for (int x = 0; x < fw; x++) {
            const int32_t d2 = m_sensedD2[m_fine.cost.index(x, y)];
            if (d2 <= reach * reach)
                take(x, y, std::sqrt(double(d2)) * fres);
        }
}

bool CGlobalPlanner::planOn(const TLevel& L, const TPoint2D& from, const TPoint2D& to,
                            bool withSensed, TGlobalPlan& p,
                            const std::vector<std::vector<TPoint2D>>* avoid) const {
    const int k = L.k;
    const double res = L.cost.resolution;
    auto cellOf = [&](const TPoint2D& q) {
        return std::make_pair(m_field.x2idx(q.x) / k, m_field.y2idx(q.y) / k);
    };
    const auto [sx, sy] = cellOf(from);
    const auto [gx, gy] = cellOf(to);
    const int32_t si = int32_t(L.cost.index(sx, sy)), gi = int32_t(L.cost.index(gx, gy));
    // the grid searched: the level's, or a copy with the sensed obstacles and
    // the ways out of a start (into a goal) nearer an obstacle than the disc
    const TCostGrid* g = &L.cost;
    auto work = [&]() -> TCostGrid& {
        if (g != &m_work) {
            m_work = L.cost;
            g = &m_work;
        }
        return m_work;
    };
    const std::vector<float>* sensed = nullptr;  // per level cell, or none
    if (withSensed && !m_seenCells.empty()) {
        sensedClearance(L, m_sensedEdge);
        sensed = &m_sensedEdge;
        auto& w = work();
        for (size_t i = 0; i < w.cost.size(); i++)
            if (m_sensedEdge[i] < kInf)
                w.cost[i] = std::max(w.cost[i], costOf(m_sensedEdge[i]));
    }
    // a cell's clearance from the map and (withSensed) the sensed obstacles
    auto clearOf = [&](size_t i) {
        return sensed ? std::min(L.clearEdge[i], (*sensed)[i]) : L.clearEdge[i];
    };
    if (avoid) {
        // the ways of earlier candidates closed (beyond the disc + 1 m of
        // the start and the goal, where every way begins and ends)
        const double ends = m_disc + 1.0, r = m_disc + 0.3;
        const int reach = int(std::ceil(r / res));
        for (const auto& way : *avoid)
            for (const auto& q : way) {
                if (std::hypot(q.x - from.x, q.y - from.y) < ends ||
                    std::hypot(q.x - to.x, q.y - to.y) < ends)
                    continue;
                auto& w = work();
                const int cx = m_field.x2idx(q.x) / k, cy = m_field.y2idx(q.y) / k;
                for (int dy = -reach; dy <= reach; dy++)
                    for (int dx = -reach; dx <= reach; dx++)
                        if (w.inside(cx + dx, cy + dy) && std::hypot(dx, dy) * res <= r)
                            w.cost[w.index(cx + dx, cy + dy)] = kInf;
            }
    }
    const float edgeCost = costOf(m_disc);
    auto openAround = [&](int cx, int cy) {
        // a start or goal nearer an obstacle than the disc: the cells within
        // the disc (+2 cells) of it that are no nearer an obstacle than it
        const float e0 = clearOf(L.cost.index(cx, cy));
        if (e0 >= m_disc)
            return;
        auto& w = work();
        const int reach = int(std::ceil(m_disc / res)) + 2;
        for (int dy = -reach; dy <= reach; dy++)
            for (int dx = -reach; dx <= reach; dx++) {
                const int x = cx + dx, y = cy + dy;
                if (!w.inside(x, y) || std::hypot(dx, dy) > reach)
                    continue;
                const size_t i = w.index(x, y);
                if (clearOf(i) >= e0 - 0.5 * res && clearOf(i) > 0 && !(w.cost[i] < kInf))
                    w.cost[i] = edgeCost;
            }
    };
    openAround(sx, sy);
    openAround(gx, gy);
    const TGridPath path = gridAStar(*g, si, gi);
    p.expanded += path.expanded;
    if (path.cells.empty())
        return false;
    p.found = true;
    p.cost = path.cost;
    p.points.clear();
    p.points.reserve(path.cells.size() + 1);
    p.points.push_back(from);
    p.minClearance = kInf;
    for (size_t q = 0; q < path.cells.size(); q++) {
        const int32_t c = path.cells[q];
        const int cx = c % L.cost.w, cy = c / L.cost.w;
        const double x = m_field.xMin() + (cx + 0.5) * res,
                     y = m_field.yMin() + (cy + 0.5) * res;
        if (q > 0 && q + 1 < path.cells.size())
            p.points.emplace_back(x, y);
    }
    p.points.push_back(to);
    // the clearance along it on the map's own cells
    for (const auto& q : p.points) {
        const int fx = m_field.x2idx(q.x), fy = m_field.y2idx(q.y);
        if (m_fine.cost.inside(fx, fy))
            p.minClearance = std::min(
                p.minClearance, double(m_fine.clearEdge[m_fine.cost.index(fx, fy)]));
    }
    p.length = geometry::polylineLength(p.points);
    return true;
}

std::vector<TGlobalPlan> CGlobalPlanner::alternatives(const TPoint2D& from,
                                                      const TPoint2D& to, int k) const {
    std::vector<TGlobalPlan> out{plan(from, to, false)};
    if (!out[0].found || k <= 1)
        return out;
    geometry::TObstacleRaster raster;
    raster.sizeX = m_field.sizeX();
    raster.sizeY = m_field.sizeY();
    raster.xMin = m_field.xMin();
    raster.yMin = m_field.yMin();
    raster.resolution = m_field.resolution();
    raster.isObstacle = [this](int cx, int cy) { return m_field.isObstacle(cx, cy); };
    std::vector<std::vector<TPoint2D>> avoid{out[0].points};
    const TLevel& L = m_coarse.k > 1 ? m_coarse : m_fine;
    // each try closes the ways found so far; a way of a class already
    // found is closed too and the search goes on (a few tries at most)
    for (int tries = 0; int(out.size()) < k && tries < 2 * k; tries++) {
        const auto t0 = std::chrono::steady_clock::now();
        TGlobalPlan c;
        if (!planOn(L, from, to, false, c, &avoid))
            break;
        c.ms =
            1e3 *
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        avoid.push_back(c.points);
        bool distinct = true;
        for (const auto& o : out)
            distinct = distinct && !geometry::sameHomotopy(o.points, c.points, raster);
        if (distinct)
            out.push_back(std::move(c));
    }
    return out;
}

std::vector<TPoint2D> CGlobalPlanner::legs(const TGlobalPlan& way) const {
    const auto& f = m_field;
    const double step = 0.5 * f.resolution();
    return geometry::simplifyDouglasPeucker(
        way.points, 0.1, [&](const TPoint2D& a, const TPoint2D& b) {
            // a leg keeps the disc's clearance (or the lesser of its ends')
            const double need =
                std::min({m_disc, f.clearanceAt(a.x, a.y), f.clearanceAt(b.x, b.y)}) -
                step;
            return geometry::segmentFree(
                a.x, a.y, b.x, b.y, step,
                [&](double x, double y) { return f.clearanceAt(x, y) < need; });
        });
}

void CGlobalPlanner::addSensed(const TPose2D& pose, const std::vector<TPoint2D>& pts,
                               double now) {
    m_now = now;
    if (!hasMap())
        return;
    const double res = m_fine.cost.resolution;
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    if (!m_timeBase)
        m_timeBase = now;
    const float t = sinceBase(now);
    // what the map explains: within a cell and a half of its obstacles
    const float explained = float(1.5 * res);
    const bool anyRemembered = !m_seenCells.empty();
    for (const auto& q : pts) {
        const double x = pose.x + c * q.x - s * q.y, y = pose.y + s * q.x + c * q.y;
        const int cx = m_field.x2idx(x), cy = m_field.y2idx(y);
        if (anyRemembered) {
            // forget what the beam to this point saw through (up to 0.15 m
            // before it: the point's own cell and its neighbour stay). The
            // beam is taken from the robot's centre, but it left the
            // sensor, which may sit up to the disc's radius off it: within
            // the disc + 0.2 m of the centre the two lines part, and the
            // centre's would pass through a post beside the robot that the
            // sensor's did not (its body then turned onto a post it had
            // seen and forgotten: a bookstore shelf's 10 cm foot).
            const double len = std::hypot(x - pose.x, y - pose.y);
            const int n = int((len - 0.15) / res);
            const int k0 = std::max(1, int(std::ceil((m_disc + 0.2) / res)));
            for (int k = k0; k <= n; k++) {
                const double f = k * res / len;
                const int bx = m_field.x2idx(pose.x + f * (x - pose.x)),
                          by = m_field.y2idx(pose.y + f * (y - pose.y));
                // not a cell sensed a moment ago: beams of two scans that
                // graze a post's corner cell mark and forget it in turn,
                // and two ways through one gap, each blocked in turn, had
                // the robot turning between them for minutes
                if (m_fine.cost.inside(bx, by))
                    if (float& at = m_seenAt[m_fine.cost.index(bx, by)];
                        !(t - at < kForgetGrace))
                        at = kNeverSeen;
            }
        }
        if (!m_fine.cost.inside(cx, cy))
            continue;
        const size_t i = m_fine.cost.index(cx, cy);
        if (m_fine.clearEdge[i] <= explained)
            continue;
        if (!liveSeen(i, now))
            m_seenCells.push_back(int32_t(i));
        m_seenAt[i] = t;
    }
    m_seenCells.erase(
        std::remove_if(m_seenCells.begin(), m_seenCells.end(),
                       [&](int32_t i) { return !liveSeen(size_t(i), now); }),
        m_seenCells.end());
    std::sort(m_seenCells.begin(), m_seenCells.end());
    m_seenCells.erase(std::unique(m_seenCells.begin(), m_seenCells.end()),
                      m_seenCells.end());
}

std::vector<TPoint2D> CGlobalPlanner::sensedNear(const TPose2D& pose,
                                                 double reach) const {
    std::vector<TPoint2D> out;
    if (!hasMap() || m_seenCells.empty())
        return out;
    const double res = m_fine.cost.resolution;
    const int r = int(std::ceil(reach / res));
    const int cx = m_field.x2idx(pose.x), cy = m_field.y2idx(pose.y);
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    for (int y = cy - r; y <= cy + r; y++)
        for (int x = cx - r; x <= cx + r; x++) {
            if (!m_fine.cost.inside(x, y) || !liveSeen(m_fine.cost.index(x, y), m_now))
                continue;
            double dx = m_field.idx2x(x) - pose.x, dy = m_field.idx2y(y) - pose.y;
            const double d = std::hypot(dx, dy);
            if (d > reach)
                continue;
            // the cell's surface may stand half a cell nearer than its centre
            const double f = d > 0.5 * res ? (d - 0.5 * res) / d : 0.0;
            dx *= f, dy *= f;
            out.emplace_back(c * dx + s * dy, -s * dx + c * dy);
        }
    return out;
}

size_t CGlobalPlanner::nearestIndex(const TPose2D& pose) const {
    // searched from the progress made on, over the next ~5 m of the plan (a
    // plan that turns round a thin wall passes near itself: the global
    // nearest point could lie on its far side)
    const auto& pts = m_plan.points;
    if (pts.empty())
        return 0;
    const size_t from = std::min(m_progress, pts.size() - 1);
    size_t best = from;
    double bestD = 1e300, along = 0;
    for (size_t k = from; k < pts.size(); k++) {
        if (k > from)
            along += std::hypot(pts[k].x - pts[k - 1].x, pts[k].y - pts[k - 1].y);
        if (along > 5.0 + options.stray_distance)
            break;
        const double d = std::hypot(pts[k].x - pose.x, pts[k].y - pose.y);
        if (d < bestD)
            bestD = d, best = k;
    }
    return best;
}

bool CGlobalPlanner::blockedAhead(const TPose2D& pose, double now) const {
    if (m_seenCells.empty() || !m_plan.found)
        return false;
    const auto& pts = m_plan.points;
    const double res = m_fine.cost.resolution;
    const int reach = int(std::ceil(m_disc / res));
    double along = 0;
    for (size_t k = nearestIndex(pose); k < pts.size(); k++) {
        if (k > 0)
            along += std::hypot(pts[k].x - pts[k - 1].x, pts[k].y - pts[k - 1].y);
        if (along > options.check_ahead)
            break;
        // Within the robot's own surroundings an obstacle beside the way is
        // its engine's business (a person passing by would replan every
        // second); one the way crosses is not (map = built: the face of a
        // wall first seen from close by, the plan through it).
        const bool near = std::hypot(pts[k].x - pose.x, pts[k].y - pose.y) < m_disc + 0.2;
        const double within = near ? 1.5 * res : m_disc - m_planSlack;
        const int r = near ? 2 : reach;
        const int cx = m_field.x2idx(pts[k].x), cy = m_field.y2idx(pts[k].y);
        for (int dy = -r; dy <= r; dy++)
            for (int dx = -r; dx <= r; dx++) {
                const int x = cx + dx, y = cy + dy;
                if (!m_fine.cost.inside(x, y) ||
                    std::hypot(dx, dy) * res - 0.5 * res >= within)
                    continue;
                if (liveSeen(m_fine.cost.index(x, y), now))
                    return true;
            }
    }
    return false;
}

std::optional<TReplanEvent> CGlobalPlanner::update(const TPose2D& pose,
                                                   const TPoint2D& target, double now) {
    m_now = now;
    if (!hasMap())
        return std::nullopt;
    std::string why;
    if (!m_target || std::hypot(target.x - m_target->x, target.y - m_target->y) > 1e-9)
        why = "new_target";
    else if (!m_plan.found)
        why = "";  // no way to this target: the navigator was told
    else if (m_lastPose && std::hypot(pose.x - m_lastPose->x, pose.y - m_lastPose->y) >
                               options.pose_jump)
        why = "pose_jump";
    else if (const size_t k = nearestIndex(pose);
             std::hypot(m_plan.points[k].x - pose.x, m_plan.points[k].y - pose.y) >
             options.stray_distance)
        why = "strayed";
    else if (now - m_lastBlockedReplan >= options.replan_interval &&
             blockedAhead(pose, now)) {
        why = "blocked";
        m_lastBlockedReplan = now;
    }
    m_lastPose = pose;
    if (why.empty()) {
        if (m_plan.found)
            m_progress = nearestIndex(pose);
        return std::nullopt;
    }
    const TPoint2D from(pose.x, pose.y);
    if (why == "new_target" && routeChooser) {
        // the route chooser picks among the best ways of distinct classes
        auto cands = alternatives(from, target, options.candidates);
        TReplanEvent ev{now, why, pose.x, pose.y, 0.0, 0.0};
        for (const auto& c : cands)
            ev.ms += c.ms;
        TRouteChoice choice;
        if (cands[0].found)
            choice = routeChooser(cands);
        m_plan = std::move(cands[std::min(choice.chosen, cands.size() - 1)]);
        m_planSlack = 0;
        ev.length = m_plan.found ? m_plan.length : 0.0;
        m_progress = 0;
        m_target = target;
        m_choices.push_back(std::move(choice));
        m_events.push_back(ev);
        return ev;
    }
    TGlobalPlan p = plan(from, target, true);
    double slack = 0;
    if (!m_seenCells.empty() && (!p.found || m_keepSeen)) {
        // the disc off the sensed points closes every way: within a cell of
        // them (their range noise; the engine keeps the robot's own shape
        // off what it senses). On a built map, also where that way is much
        // the shorter: its sensed walls are all it knows, and a gap sensed a
        // cell too narrow sent the robot exploring a detour of ten times
        // the way (MRPT's localization_demo map: 52 m driven for 5 m).
        m_sensedSlack = m_fine.cost.resolution;
        TGlobalPlan q = plan(from, target, true);
        m_sensedSlack = 0;
        q.ms += p.ms;
        if (!p.found || (q.found && p.length > kDetourRatio * q.length + 1.0)) {
            p = std::move(q);
            slack = m_fine.cost.resolution;
        } else
            p.ms = q.ms;
    }
    if (!p.found && !m_seenCells.empty() && !m_keepSeen) {
        // the sensed obstacles close every way: the map's way, round which
        // the engine avoids what it senses (people move on). Not on a built
        // map, whose sensed obstacles are all it knows of the world.
        TGlobalPlan q = plan(from, target, false);
        q.ms += p.ms;
        if (q.found || why == "new_target") {
            p = std::move(q);
            slack = 0;
        }
    }
    TReplanEvent ev{now, why, pose.x, pose.y, p.found ? p.length : 0.0, p.ms};
    if (why == "new_target" || p.found) {
        m_planSlack = slack;
        m_plan = std::move(p);
        m_progress = 0;
        m_target = target;
    }
    m_events.push_back(ev);
    return ev;
}

std::optional<TPoint2D> CGlobalPlanner::guidePoint(const TPose2D& pose) const {
    if (!m_plan.found || m_plan.points.size() < 2)
        return std::nullopt;
    const auto& pts = m_plan.points;
    const size_t k0 = nearestIndex(pose);
    // the stretch from the nearest point on (the look-ahead searches from
    // its own nearest point: a plan passing near itself must not let it jump)
    double along = 0;
    size_t k1 = k0;
    while (k1 + 1 < pts.size() && along < 2 * options.lookahead + 1) {
        along += std::hypot(pts[k1 + 1].x - pts[k1].x, pts[k1 + 1].y - pts[k1].y);
        k1++;
    }
    const std::vector<TPoint2D> stretch(pts.begin() + long(k0),
                                        pts.begin() + long(k1) + 1);
    if (stretch.size() < 2)
        return pts.back();
    const auto la = geometry::lookaheadOnPolyline(
        stretch, TPoint2D(pose.x, pose.y), options.lookahead,
        0.5 * m_fine.cost.resolution, [&](double x, double y) {
            const int cx = m_field.x2idx(x), cy = m_field.y2idx(y);
            return m_fine.cost.inside(cx, cy)
                       ? double(m_fine.clearEdge[m_fine.cost.index(cx, cy)])
                       : 0.0;
        });
    return stretch[la.ahead];
}

double CGlobalPlanner::remainingLength(const TPose2D& pose) const {
    if (!m_plan.found || m_plan.points.empty())
        return std::numeric_limits<double>::infinity();
    const auto& pts = m_plan.points;
    const size_t k0 = nearestIndex(pose);
    double rest = std::hypot(pts[k0].x - pose.x, pts[k0].y - pose.y);
    for (size_t k = k0 + 1; k < pts.size(); k++)
        rest += std::hypot(pts[k].x - pts[k - 1].x, pts[k].y - pts[k - 1].y);
    return rest;
}
}  // namespace risknav::planning
