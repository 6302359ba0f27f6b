#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/geometry/polyline.h>
#include <risknav/viewpoint/CViewpointPlanner.h>
#include <risknav/viewpoint/CVisibilityGraph.h>

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <random>
#include <thread>

using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
using namespace risknav::common;

namespace risknav::viewpoint {
void CViewpointPlanner::loadFromConfigFile(const CIniConfig& c) {
    m_where = c.path();
    for (const auto& s : c.sections())
        if (s != "ViewpointPlan" && s != "Camera" && s != "Robot")
            c.throwUnknownSection(s, "ViewpointPlan, Camera, Robot");
    if (!c.sectionExists("ViewpointPlan"))
        throw CBadInputError(c.path() + ": missing section [ViewpointPlan]");
    loadOptions(options, c, "ViewpointPlan");
    loadOptions(camera, c, "Camera");
    loadOptions(robot, c, "Robot");
    c.throwOnUnreadKeys();
    TPolygonWorld w = loadPolygonWorld(options.world_file, options.map.map_file.empty());
    if (!options.map.map_file.empty()) {
        const auto grid = loadOccupancyGrid(options.map);
        if (!(w.xMax > w.xMin && w.yMax > w.yMin)) {
            w.xMin = grid.getXMin();
            w.xMax = grid.getXMax();
            w.yMin = grid.getYMin();
            w.yMax = grid.getYMax();
        }
        for (auto& o : obstaclesFromGrid(grid, options.rule, options.contour_tolerance))
            w.obstacles.push_back(std::move(o));
        // The traced contour runs up to a cell and a half (dilation, cell
        // centres) plus the simplification outside the wall the user put the
        // landmark on.
        snapLandmarksToWalls(w, 2.0 * grid.getResolution() + options.contour_tolerance);
    }
    validateWorld(w, options.world_file);
    m_world = std::move(w);
    prepare();
    // Work the input cannot justify is refused before it starts.
    if (const size_t n = cornerNodeCount(); n > kMaxGraphNodes)
        throwBadKey(c, "ViewpointPlan", "corner_segments",
                    std::to_string(options.corner_segments),
                    "the world's convex corners give " + std::to_string(n) +
                        " C-obstacle nodes (at most " + std::to_string(kMaxGraphNodes) +
                        "): fewer or simpler obstacles, or fewer corner segments");
    const double diagonal =
        std::hypot(m_world.xMax - m_world.xMin, m_world.yMax - m_world.yMin);
    if (diagonal / options.sample_step > kMaxSamplesPerPath / 4)
        throwBadKey(
            c, "ViewpointPlan", "sample_step", numberText(options.sample_step),
            "the world's diagonal (" + numberText(diagonal) +
                " m) would take more than 500000 samples per path; use a larger step");
    // The three together (each alone within its bound above): 360 corner
    // segments, 100 paths and 1 mm samples on an 8 x 6 m world ran 369 s.
    // Sample evaluations (paths x samples along each, at most the diagonal's
    // worth a path as a rough measure) and Yen's searches on the corner graph
    // (paths x nodes^2) over the sweep, each bounded.
    {
        const double nS = double(options.safety_margins.size()),
                     k = double(options.k_paths), nodes = double(cornerNodeCount());
        const double samples = nS * k * diagonal / options.sample_step;
        if (samples > 2e6)
            throwBadKey(c, "ViewpointPlan", "k_paths", std::to_string(options.k_paths),
                        std::to_string(options.safety_margins.size()) + " S x " +
                            std::to_string(options.k_paths) + " paths x " +
                            numberText(std::round(diagonal / options.sample_step)) +
                            " samples (the diagonal at sample_step) = " +
                            numberText(std::round(samples)) +
                            ", at most 2e+06: fewer paths or S, or a larger sample_step");
        const double graph = nS * k * nodes * nodes;
        if (graph > 5e8)
            throwBadKey(c, "ViewpointPlan", "k_paths", std::to_string(options.k_paths),
                        std::to_string(options.safety_margins.size()) + " S x " +
                            std::to_string(options.k_paths) + " paths x " +
                            numberText(nodes) +
                            "^2 corner nodes = " + numberText(std::round(graph)) +
                            ", at most 5e+08: fewer paths or S, or fewer "
                            "corner_segments");
    }
    // The robot itself must fit at start and goal: a user error, not a result.
    for (const bool isStart : {true, false}) {
        const TPoint2D p = isStart ? options.start : options.goal;
        const char* key = isStart ? "start" : "goal";
        if (m_world.insideObstacle(p))
            throwBadKey(c, "ViewpointPlan", key, numberText(p.x) + " " + numberText(p.y),
                        std::string(isStart ? "the start" : "the goal") + " (" +
                            numberText(p.x) + ", " + numberText(p.y) +
                            ") lies inside an obstacle or outside the bounds");
        if (allowedError(p.x, p.y) < 0)
            throwBadKey(c, "ViewpointPlan", key, numberText(p.x) + " " + numberText(p.y),
                        std::string(isStart ? "the start" : "the goal") + " (" +
                            numberText(p.x) + ", " + numberText(p.y) +
                            ") is nearer an obstacle than the robot radius " +
                            numberText(robot.radius) + " m");
    }
}

void CViewpointPlanner::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    options.saveToConfigFile(c, "ViewpointPlan");
    camera.saveToConfigFile(c, "Camera");
    robot.saveToConfigFile(c, "Robot");
}

void CViewpointPlanner::setWorld(TPolygonWorld w) {
    validateWorld(w, "(world)");
    m_world = std::move(w);
    prepare();
}

size_t CViewpointPlanner::cornerNodeCount() const {
    const double step = 2 * M_PI / options.corner_segments;
    size_t n = 0;
    for (const auto& r : m_world.rings())
        for (size_t i = 0; i < r.size(); i++) {
            const TPoint2D& a = r[(i + r.size() - 1) % r.size()];
            const TPoint2D& v = r[i];
            const TPoint2D& b = r[(i + 1) % r.size()];
            const double ein = std::atan2(v.y - a.y, v.x - a.x);
            const double turn =
                mrpt::math::wrapToPi(std::atan2(b.y - v.y, b.x - v.x) - ein);
            if (turn > 0)
                n += size_t(std::max(1.0, std::ceil(turn / step - 1e-12)));
        }
    return n;
}

void CViewpointPlanner::prepare() {
    // Cell about the safety distance: the C-space queries look that far.
    const double span =
        std::max(m_world.xMax - m_world.xMin, m_world.yMax - m_world.yMin);
    m_index = geometry::CSegmentIndex(m_world.edges(), std::max(0.25, span / 64));
    m_refs = m_world.obstacleReferencePoints();
}

double CViewpointPlanner::allowedError(double x, double y) const {
    return m_index.distance({x, y}, std::numeric_limits<double>::infinity()) -
           robot.radius;
}

TPointEvaluation CViewpointPlanner::evaluate(const std::vector<TPathSample>& samples,
                                             size_t i, bool bestOnly) const {
    TPointEvaluation ev;
    const TPathSample& p = samples[i];
    const TPose2D pose{p.x, p.y, p.heading};
    const TCameraRig rig = camera.rig();
    const TImageErrors err = camera.errors();
    const auto views = landmarkViews(pose, m_world.landmarks, rig, m_index);
    auto obs = enumerateObservations(pose, m_world.landmarks, views, rig);
    ev.observations = obs.size();
    // The cheap closed-form strategies first: their reach bounds the costly
    // three-landmark Newton solves sooner.
    std::stable_sort(
        obs.begin(), obs.end(), [](const TObservation& a, const TObservation& b) {
            auto rank = [](TStrategy s) {
                return s == TStrategy::TwoLandmark ? 0 : s == TStrategy::Stereo ? 1 : 2;
            };
            return rank(a.strategy) < rank(b.strategy);
        });
    const double dr = options.dead_reckoning;
    // The reach only shrinks as the errors grow: an observation whose errors
    // so far already reach no further than the best is done.
    std::function<bool(double, double)> giveUp;
    if (bestOnly)
        giveUp = [&](double ePos, double dPhi) {
            return ev.best && reachFrom(samples, i, ePos, dPhi, dr) <= ev.best->reach;
        };
    for (const auto& o : obs) {
        TStrategyChoice ch{
            o, worstCaseError(o, pose, m_world.landmarks, rig, err, giveUp), -1};
        if (ch.err.gaveUp)
            continue;
        if (!ch.err.ok) {
            ev.degenerate++;
            continue;
        }
        ch.reach = reachFrom(samples, i, ch.err.ePos, ch.err.dPhi, dr);
        if (ch.reach < 0)
            continue;
        auto& slot = ev.perStrategy[size_t(o.strategy) - size_t('A')];
        if (!slot || ch.reach > slot->reach)
            slot = ch;
        if (!ev.best || ch.reach > ev.best->reach)
            ev.best = ch;
    }
    return ev;
}

TPlanRow CViewpointPlanner::planPath(const std::vector<TPoint2D>& path, double S) const {
    TPlanRow row;
    row.S = S;
    row.path = path;
    row.length = geometry::polylineLength(path);
    const auto samples = samplePath(path, options.sample_step, [&](double x, double y) {
        return allowedError(x, y);
    });
    row.minAllowed = std::numeric_limits<double>::infinity();
    for (const auto& s : samples)
        row.minAllowed = std::min(row.minAllowed, s.allowed);
    std::map<size_t, TPointEvaluation> memo;
    auto bestReach = [&](size_t i) {
        auto it = memo.find(i);
        if (it == memo.end())
            it = memo.emplace(i, evaluate(samples, i, true)).first;
        return it->second.best ? it->second.best->reach : -1.0;
    };
    const auto g = planViewpointsGreedy(
        samples, options.start_error, options.start_heading_error_deg * M_PI / 180,
        options.dead_reckoning, bestReach, !options.exhaustive);
    row.feasible = g.feasible;
    row.reach = g.reach;
    row.evaluations = g.evaluations;
    for (const auto& [i, ev] : memo)
        row.degenerate += ev.degenerate;
    // Where the plan fails: the sample at the reach.
    {
        size_t k = 0;
        while (k + 1 < samples.size() && samples[k + 1].s <= g.reach)
            k++;
        row.failAt = {samples[k].x, samples[k].y};
    }
    for (size_t v = 0; v < g.viewpoints.size(); v++) {
        const size_t i = g.viewpoints[v];
        // The chosen viewpoints again in full: every strategy's best there.
        TPlannedViewpoint pv{samples[i], evaluate(samples, i, false), 0};
        const double next = v + 1 < g.viewpoints.size() ? samples[g.viewpoints[v + 1]].s
                                                        : samples.back().s;
        pv.m = next - samples[i].s;
        row.viewpoints.push_back(std::move(pv));
    }
    return row;
}

void CViewpointPlanner::plan() {
    m_sweep.assign(options.safety_margins.size(), {});
    const TPoint2D start = options.start, goal = options.goal;
    std::atomic<size_t> next{0};
    std::mutex failMutex;
    std::exception_ptr failure;  // the first worker's exception, rethrown after the join
    auto work = [&]() {
        try {
            for (size_t k; (k = next++) < m_sweep.size();) {
                TSweepPoint& sp = m_sweep[k];
                sp.S = options.safety_margins[k];
                const CVisibilityGraph g(m_world, m_index, robot.radius + sp.S,
                                         options.corner_segments, start, goal);
                sp.startFree = g.startFree();
                sp.goalFree = g.goalFree();
                sp.nodes = g.nodes().size();
                sp.edges = g.edges().size();
                for (const auto& e : g.edges())
                    sp.graphEdges.push_back({g.nodes()[e.a].p, g.nodes()[e.b].p});
                const auto paths = g.kShortestPaths(size_t(options.k_paths));
                for (size_t r = 0; r < paths.size(); r++) {
                    sp.rows.push_back(planPath(paths[r], sp.S));
                    sp.rows.back().rank = r;
                }
            }
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failMutex);
            if (!failure)
                failure = std::current_exception();
            next = m_sweep.size();  // the others stop too
        }
    };
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const size_t nThreads = std::min(
        m_sweep.size(), size_t(options.threads > 0 ? unsigned(options.threads) : hw));
    std::vector<std::thread> pool;
    for (size_t t = 1; t < nThreads; t++)
        pool.emplace_back(work);
    work();
    for (auto& t : pool)
        t.join();
    if (failure)
        std::rethrow_exception(failure);
    assignRoutes();
    std::vector<const TPlanRow*> all;
    for (const auto& sp : m_sweep)
        for (const auto& row : sp.rows)
            all.push_back(&row);
    m_optimal.reset();
    if (const TPlanRow* b = bestPlan(all, options.length_tolerance))
        for (size_t k = 0; k < m_sweep.size(); k++)
            for (size_t r = 0; r < m_sweep[k].rows.size(); r++)
                if (&m_sweep[k].rows[r] == b)
                    m_optimal = {k, r};
}

const TPlanRow* bestPlan(const std::vector<const TPlanRow*>& rows, double tolerance) {
    double shortest = std::numeric_limits<double>::infinity();
    for (const TPlanRow* r : rows)
        if (r->feasible)
            shortest = std::min(shortest, r->length);
    const TPlanRow* best = nullptr;
    for (const TPlanRow* r : rows) {
        if (!r->feasible || r->length > shortest + tolerance)
            continue;
        if (!best || r->viewpoints.size() < best->viewpoints.size() ||
            (r->viewpoints.size() == best->viewpoints.size() &&
             (r->S > best->S || (r->S == best->S && r->length < best->length))))
            best = r;
    }
    return best;
}

void CViewpointPlanner::assignRoutes() {
    // Homotopy class of a path: the winding numbers, around a point inside
    // every obstacle, of the loop path + the straight line back to the start
    // (windingNumber closes the loop itself).
    auto signature = [&](const std::vector<TPoint2D>& path) {
        std::vector<int> sig;
        for (const auto& p : m_refs)
            sig.push_back(geometry::windingNumber(path, p));
        return sig;
    };
    std::map<std::vector<int>, double> shortest;
    for (auto& sp : m_sweep)
        for (auto& row : sp.rows) {
            const auto sig = signature(row.path);
            auto it = shortest.find(sig);
            if (it == shortest.end() || row.length < it->second)
                shortest[sig] = row.length;
        }
    std::vector<std::pair<double, std::vector<int>>> order;
    for (const auto& [sig, L] : shortest)
        order.push_back({L, sig});
    std::sort(order.begin(), order.end());
    std::map<std::vector<int>, int> id;
    for (size_t i = 0; i < order.size(); i++)
        id[order[i].second] = int(i) + 1;
    for (auto& sp : m_sweep)
        for (auto& row : sp.rows)
            row.route = id[signature(row.path)];
    m_routeCount = order.size();
}

CViewpointPlanner::TMonteCarlo CViewpointPlanner::monteCarlo(const TPlanRow& row,
                                                             size_t draws,
                                                             uint64_t seed) const {
    TMonteCarlo mc;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(-1, 1);
    const TCameraRig rig = camera.rig();
    const TImageErrors err = camera.errors();
    for (const auto& vp : row.viewpoints) {
        if (!vp.eval.best)
            continue;
        const TStrategyChoice& ch = *vp.eval.best;
        const TPose2D pose{vp.at.x, vp.at.y, vp.at.heading};
        const TMeasurement z0 = predictMeasurement(ch.obs, pose, m_world.landmarks, rig);
        const auto dz = measurementErrors(ch.obs, err);
        const double bound = totalError(ch.err, vp.m);
        for (size_t d = 0; d < draws; d++) {
            TMeasurement z = z0;
            for (size_t k = 0; k < z.size(); k++)
                z[k] += dz[k] * uni(rng);
            mc.draws++;
            const auto p = solvePose(ch.obs, z, m_world.landmarks, rig, pose);
            if (!p) {
                mc.failures++;
                continue;
            }
            const double ePos = std::hypot(p->x - pose.x, p->y - pose.y);
            const double dPhi = std::abs(mrpt::math::wrapToPi(p->phi - pose.phi));
            // Error-free images give bounds of rounding size: no ratio then.
            if (ch.err.ePos > 1e-12)
                mc.maxRatioPos = std::max(mc.maxRatioPos, ePos / ch.err.ePos);
            if (bound > 1e-12)
                mc.maxRatioTotal =
                    std::max(mc.maxRatioTotal, (ePos + angularError(vp.m, dPhi)) / bound);
        }
    }
    return mc;
}

}  // namespace risknav::viewpoint
