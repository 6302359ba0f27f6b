#include <risknav/common/CQuadHeap.h>
#include <risknav/speed/CAdaptiveSpeedController.h>
#include <risknav/speed/speed_rules.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>

namespace risknav::speed {
const char* reasonName(TSpeedReason r) {
    switch (r) {
        case TSpeedReason::None:
            return "none";
        case TSpeedReason::Narrow:
            return "narrow";
        case TSpeedReason::Undecided:
            return "undecided";
        case TSpeedReason::Unreachable:
            return "unreachable";
    }
    return "?";
}

CAdaptiveSpeedController::CAdaptiveSpeedController(
    const TSpeedControlOptions& o, double robotRadius, int necessaryObservations,
    std::shared_ptr<const IPathPlanner> planner)
    : m_o(o), m_radius(robotRadius), m_N(necessaryObservations), m_planner(planner) {
    m_o.validate();
    if (!(robotRadius > 0) || necessaryObservations < 1)
        throw std::invalid_argument("speed controller: radius > 0 and N >= 1 needed");
    if (!m_planner)
        m_planner = std::make_shared<CGridPathPlanner>();
}

void CAdaptiveSpeedController::checkWayOnReach(const TPlanningField& field) const {
    if (!(field.wayOnReach >= wayOnBand(field.map.resolution)))
        throw std::invalid_argument(
            "speed controller: the planning field's wayOnDist ends before the band");
}

bool CAdaptiveSpeedController::chooseTarget(const TPlanningField& field,
                                            const mrpt::math::TPoint2D& start,
                                            const mrpt::math::TPoint2D& goal,
                                            mrpt::math::TPoint2D& target, bool& temporary,
                                            const TTargetHints& hints) const {
    const TGoalCost& goalCost = hints.goalCost;
    const auto& m = field.map;
    const double res = m.resolution;
    const double inflation = m_radius + m_o.margins.back();
    const int si = m.x2idx(start.x), sj = m.y2idx(start.y);
    if (!m.inside(si, sj))
        return false;
    // the cells the slowest speed can reach (the planner's escape rule
    // included), in order of path length from the start (Dijkstra, 8-connected)
    const CTraversable traversable(field, si, sj, inflation, true);
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> g(m.cells.size(), inf);
    using TEntry = std::pair<double, size_t>;
    // (g, cell) pairs are all distinct (a cell is pushed again only with a
    // lower g), so any exact min-heap pops the same sequence
    common::CQuadHeap<TEntry, std::greater<TEntry>> open;
    g[m.index(si, sj)] = 0;
    open.emplace(0.0, m.index(si, sj));
    const int gi = m.x2idx(goal.x), gj = m.y2idx(goal.y);
    bool goalReached = false;
    double bestCost = inf, nearestDist = inf, bestStraight = inf;
    mrpt::math::TPoint2D nearest, straightTarget;
    const double band = wayOnBand(res);
    checkWayOnReach(field);
    const std::vector<float>& wayOnDist = field.wayOnDist();
    // Early ends (a speed-up; the result is the full search's): the goal
    // popped with its margin is the answer; and where neither the goal nor
    // the point nearest it can be the answer, no cell popped after the best
    // candidate's cost can beat it (a candidate's cost is >= its path length).
    const bool goalInside = m.inside(gi, gj);
    const bool goalCanBePopped =
        goalInside && ((gi == si && gj == sj) || traversable(gi, gj));
    const bool nearestMayCount =
        goalInside && m.cells[m.index(gi, gj)] == mapping::TFusedCell::Free;
    const bool pruneByCost = !goalCanBePopped && !nearestMayCount;
    while (!open.empty()) {
        const auto [gk, k] = open.top();
        open.pop();
        if (gk > g[k])
            continue;
        const int i = int(k % size_t(m.size)), j = int(k / size_t(m.size));
        if (i == gi && j == gj) {
            goalReached = true;
            if (field.clearance[k] >= inflation)
                break;
        }
        if (pruneByCost && gk > bestCost)
            break;
        // libm's hypot only where the squared distance cannot decide (a
        // speed-up: one per popped cell was a tenth of the cycle)
        const double gx = m.idx2x(i) - goal.x, gy = m.idx2y(j) - goal.y;
        double toGoal = -1;
        auto distToGoal = [&] {
            if (toGoal < 0)
                toGoal = std::hypot(gx, gy);
            return toGoal;
        };
        if (!(gx * gx + gy * gy > nearestDist * nearestDist * (1 + 1e-9)) &&
            distToGoal() < nearestDist) {
            nearestDist = toGoal;
            nearest = {m.idx2x(i), m.idx2y(j)};
        }
        // Beyond the paper (which takes the boundary point nearest the goal
        // in a straight line): path to it + the cost on from it, over the
        // open frontier and the map's edge
        if (wayOnDist[k] <= band) {
            distToGoal();
            const double straight = gk + m_o.frontier_goal_weight * toGoal;
            if (straight < bestStraight) {
                bestStraight = straight;
                straightTarget = {m.idx2x(i), m.idx2y(j)};
            }
            const double sw =
                hints.previous && std::hypot(m.idx2x(i) - hints.previous->x,
                                             m.idx2y(j) - hints.previous->y) > 1.0
                    ? m_o.target_switch_cost
                    : 0.0;
            const double cost =
                sw + (goalCost ? gk + goalCost(m.idx2x(i), m.idx2y(j)) : straight);
            if (cost < bestCost) {
                bestCost = cost;
                target = {m.idx2x(i), m.idx2y(j)};
            }
        }
        for (int dj = -1; dj <= 1; dj++)
            for (int di = -1; di <= 1; di++) {
                const int ni = i + di, nj = j + dj;
                if ((di == 0 && dj == 0) || !m.inside(ni, nj) || !traversable(ni, nj))
                    continue;
                const size_t nk = m.index(ni, nj);
                const double ng = gk + (di != 0 && dj != 0 ? M_SQRT2 : 1.0) * res;
                if (ng < g[nk]) {
                    g[nk] = ng;
                    open.emplace(ng, nk);
                }
            }
    }
    if (goalReached && field.clearance[m.index(gi, gj)] >= inflation) {
        target = goal;
        temporary = false;
        return true;
    }
    // a goal in known free space but nearer an obstacle than the slowest
    // margin: the reachable point nearest it (within that margin)
    if (m.inside(gi, gj) && m.cells[m.index(gi, gj)] == mapping::TFusedCell::Free &&
        nearestDist <= inflation + res) {
        target = nearest;
        temporary = false;
        return true;
    }
    temporary = true;
    if (!std::isfinite(bestCost) && std::isfinite(bestStraight)) {
        // goalCost knows no way on from any candidate (a memory that walled
        // the robot in, e.g. a destination moved by drift): the straight line
        target = straightTarget;
        return true;
    }
    return std::isfinite(bestCost);
}

TSpeedDecision CAdaptiveSpeedController::decide(const TPlanningField& field,
                                                const mrpt::math::TPose2D& robot,
                                                const mrpt::math::TPoint2D& goal,
                                                int fixedIndex,
                                                const TTargetHints& hints) const {
    TSpeedDecision d;
    const mrpt::math::TPoint2D start(robot.x, robot.y);
    const size_t nSpeeds = m_o.speeds.size();
    if (fixedIndex >= int(nSpeeds))
        throw std::invalid_argument("speed controller: no such fixed speed");
    // every clearance read below is compared with an inflation
    if (!(field.clearanceReach >= m_radius + m_o.margins.front()))
        throw std::invalid_argument(
            "speed controller: the planning field's clearance ends before the widest "
            "inflation");
    const double res = field.map.resolution;
    const size_t slowest = nSpeeds - 1;
    checkWayOnReach(field);
    // Beyond the paper, a speed-up with the same decisions: a goal in known
    // free space is the target iff chooseTarget()'s flood pops it with the
    // slowest margin, i.e. iff the slowest speed's plan to it (the same
    // cells: CTraversable) reaches it and it keeps that margin; that plan
    // answers in a few hundred cells where the flood took thousands.
    const int gi = field.map.x2idx(goal.x), gj = field.map.y2idx(goal.y);
    std::optional<TPlannedPath> slowToGoal;
    bool chosen = false;
    if (field.map.inside(gi, gj) &&
        field.map.cells[field.map.index(gi, gj)] == mapping::TFusedCell::Free) {
        slowToGoal = m_planner->plan(field, start, goal, inflation(slowest), 0.0, true);
        if (slowToGoal->reached &&
            field.clearance[field.map.index(gi, gj)] >= inflation(slowest)) {
            d.target = goal;
            d.temporaryTarget = false;
            chosen = true;
        }
    }
    if (!chosen)
        chosen = chooseTarget(field, start, goal, d.target, d.temporaryTarget, hints);
    if (!chosen) {
        d.reason = TSpeedReason::Unreachable;
        return d;
    }
    d.nearestToGoal =
        !d.temporaryTarget && std::hypot(d.target.x - goal.x, d.target.y - goal.y) > 1e-9;
    auto undecidedDistance = [&](const TPlannedPath& p, size_t k) {
        return undecidedAlong(p, field, d, k);
    };
    auto tolerance = [&](size_t k) { return targetTolerance(d, k, res); };

    // the slowest speed's plan to the target: the one made above when the
    // target is the goal
    auto slowestToTarget = [&] {
        if (slowToGoal && !d.temporaryTarget && d.target.x == goal.x &&
            d.target.y == goal.y)
            return std::move(*slowToGoal);
        return m_planner->plan(field, start, d.target, inflation(slowest),
                               tolerance(slowest), true);
    };

    if (fixedIndex >= 0) {
        const size_t k = size_t(fixedIndex);
        d.perSpeed.assign(nSpeeds, TPlannedPath{});
        d.perSpeed[k] = k == slowest ? slowestToTarget()
                                     : m_planner->plan(field, start, d.target,
                                                       inflation(k), tolerance(k), true);
        d.path = d.perSpeed[k];
        if (!d.path.reached) {
            // the fixed robot has no path with its margin: it goes with its size only
            const TPlannedPath tight =
                m_planner->plan(field, start, d.target, m_radius, tolerance(k), true);
            if (tight.reached) {
                d.path = tight;
                d.marginBroken = true;
            }
        }
        d.pathIndex = int(k);
        d.dUndecided = undecidedDistance(d.path, k);
        if (d.path.length < 0.5 * res && !d.path.reached) {
            d.reason = TSpeedReason::Unreachable;
            return d;
        }
        d.speed = m_o.speeds[k];
        d.speedIndex = int(k);
        d.reason = TSpeedReason::None;
        return d;
    }

    planEverySpeed(field, start, d, slowestToTarget);
    std::vector<double> costs(nSpeeds);
    for (size_t k = 0; k < nSpeeds; k++)
        costs[k] = d.perSpeed[k].costToGo;
    d.safeByGap = safeSpeedsByGap(costs, m_o.gap_threshold);
    const size_t owner = d.safeByGap.front();  // the fastest safe speed owns the path
    d.pathIndex = int(owner);
    d.path = d.perSpeed[owner];
    if (d.path.length < 0.5 * res && !d.path.reached) {
        d.reason = TSpeedReason::Unreachable;
        return d;
    }
    chooseSpeed(field, owner, d);
    return d;
}

void CAdaptiveSpeedController::planEverySpeed(
    const TPlanningField& field, const mrpt::math::TPoint2D& start, TSpeedDecision& d,
    const std::function<TPlannedPath()>& slowestToTarget) const {
    const size_t nSpeeds = m_o.speeds.size(), slowest = nSpeeds - 1;
    const double res = field.map.resolution;
    d.perSpeed.assign(nSpeeds, TPlannedPath{});
    if (!d.temporaryTarget) {
        // Beyond the paper, a speed-up with the same decisions: to a
        // destination (tolerance 0 for every speed) the plans go slowest
        // first, each faster one bounded by what the gap rule can use: a
        // cost-to-go more than gap_threshold above every slower speed's
        // puts the speed, and every faster one (a larger margin is never
        // cheaper: IPathPlanner), beyond the split (safeSpeedsByGap()), as a
        // +inf does. Searched out, such a plan was most of the cycle (the
        // fastest speed's margin fits nowhere near the destination).
        d.perSpeed[slowest] = slowestToTarget();
        double slowerMax = d.perSpeed[slowest].costToGo;
        bool cut = false;
        for (size_t k = slowest; k-- > 0;) {
            TPlannedPath& p = d.perSpeed[k];
            if (cut) {
                p.points = {start};
                p.cutOff = true;
                continue;
            }
            p = m_planner->plan(field, start, d.target, inflation(k), 0.0, false,
                                slowerMax + m_o.gap_threshold);
            cut = p.cutOff;
            if (!cut)
                slowerMax = std::max(slowerMax, p.costToGo);
        }
    } else {
        common::parallelFor(m_parallel, nSpeeds, [&](size_t k) {
            d.perSpeed[k] = m_planner->plan(field, start, d.target, inflation(k),
                                            targetTolerance(d, k, res), k == slowest);
        });
    }
}

double CAdaptiveSpeedController::undecidedAlong(const TPlannedPath& p,
                                                const TPlanningField& field,
                                                const TSpeedDecision& d, size_t k) const {
    double du = distanceToUndecided(p, field, inflation(k));
    if (d.temporaryTarget)
        du = std::min(du, p.length);
    return du;
}

void CAdaptiveSpeedController::chooseSpeed(const TPlanningField& field, size_t owner,
                                           TSpeedDecision& d) const {
    auto undecidedDistance = [&](const TPlannedPath& p, size_t k) {
        return undecidedAlong(p, field, d, k);
    };
    // section 4.2: faster speeds whose margin holds along the next cycles
    for (size_t k = 0; k < owner; k++)
        if (clearanceHoldsAhead(d.path, field, inflation(k),
                                m_o.lookahead_cycles * m_o.speeds[k] * m_o.cycle_time))
            d.allowed.push_back(k);
    for (size_t k : d.safeByGap)
        d.allowed.push_back(k);
    d.dUndecided = undecidedDistance(d.path, owner);
    bool undecidedCut = false;
    for (size_t k : d.allowed) {  // fastest first
        if (undecidedRuleHolds(undecidedDistance(d.path, k), m_o.speeds[k],
                               m_o.cycle_time, m_N)) {
            d.speed = m_o.speeds[k];
            d.speedIndex = int(k);
            d.reason = k == 0         ? TSpeedReason::None
                       : undecidedCut ? TSpeedReason::Undecided
                                      : TSpeedReason::Narrow;
            return;
        }
        undecidedCut = true;
    }
    d.reason = TSpeedReason::Undecided;  // even the slowest would reach it too soon
}
}  // namespace risknav::speed
