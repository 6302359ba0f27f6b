#include <risknav/common/config_read.h>
#include <risknav/sim/CAgentsSim.h>

#include <algorithm>
#include <cmath>

using namespace risknav::common;
using mrpt::math::TPoint2D;

namespace risknav::sim {
namespace {
bool startsWithNumbered(const std::string& s, const std::string& prefix) {
    if (s.size() <= prefix.size() || s.compare(0, prefix.size(), prefix) != 0)
        return false;
    return std::all_of(s.begin() + prefix.size(), s.end(),
                       [](unsigned char ch) { return std::isdigit(ch); });
}

std::string pathText(const std::vector<TPoint2D>& p) {
    std::string t;
    for (const auto& q : p)
        t += (t.empty() ? "" : " ") + numberText(q.x) + " " + numberText(q.y);
    return t;
}

const TRange kCoordinate = TRange::closed(-1e6, 1e6, "m");
// a person's path: a polyline of at least two points
const CDeclaredOptions::TCount kPathCount{2, 1, 0, true};

void checkDistinctPoints(const std::string& s, const std::vector<TPoint2D>& p) {
    for (size_t i = 1; i < p.size(); i++)
        checkRule(std::hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y) >= 1e-6, s, "path",
                  pathText(p), "has two equal consecutive points");
}
}  // namespace

bool CAgentsSim::ownsSection(const std::string& s) {
    return startsWithNumbered(s, "DoorPedestrian") ||
           startsWithNumbered(s, "CorridorWalker") || startsWithNumbered(s, "Clutter");
}

void CAgentsSim::TDoorPedestrian::declare(Visitor& v) {
    // the file's list in a local: door[] keeps its bits unless a load changed it
    const std::vector<double> held(door, door + 4);
    std::vector<double> seg = held;
    v.numbers(seg, "door", kCoordinate,
              "the doorway segment x1 y1 x2 y2 (drawn, and the trigger point)",
              TCount{0, 1, 4, true});
    if (seg != held && seg.size() == 4)
        std::copy(seg.begin(), seg.end(), door);
    v.points(path, "path", kCoordinate,
             "x y pairs from inside the room into and along the corridor; the person "
             "leaves at its end",
             kPathCount);
    // people's paces (1e308 m/s teleported a person past the robot in one step)
    v.number(speed, "speed", TRange{0, 10, true, false, "m/s"}, "walking speed");
    v.number(radius, "radius", TRange::closed(0.05, 2, "m"), "the person's disc");
    v.number(patience, "patience", TRange{0, 1e5, true, false, "s"},
             "a person who cannot move at all for this long goes away");
    v.choice(emergence, "emergence", {"poisson", "schedule", "trigger"},
             "when the person comes out");
    v.number(rate_per_min, "rate_per_min", TRange{0, 600, true, false, "1/min"},
             "poisson: mean emergence rate");
    v.numbers(schedule, "schedule", TRange::nonNegative("s"),
              "schedule: emergence times since the start, increasing");
    v.number(trigger_distance, "trigger_distance", TRange{0, 1000, true, false, "m"},
             "trigger: the robot came this close to the door's middle");
    v.number(trigger_probability, "trigger_probability", TRange::closed(0, 1),
             "trigger: chance of an emergence per pass of the robot");
}

void CAgentsSim::TDoorPedestrian::validateRules() const {
    const std::string& s = section;
    checkDistinctPoints(s, path);
    std::string sched;
    for (double x : schedule)
        sched += (sched.empty() ? "" : " ") + numberText(x);
    checkRule(std::is_sorted(schedule.begin(), schedule.end()), s, "schedule", sched,
              "times must be increasing");
    checkRule(emergence != "schedule" || !schedule.empty(), s, "schedule", sched,
              "required when emergence = schedule");
}

void CAgentsSim::TWalker::declare(Visitor& v) {
    v.points(path, "path", kCoordinate, "x y pairs the walkers follow", kPathCount);
    v.number(speed_min, "speed_min", TRange{0, 10, true, false, "m/s"}, "slowest walker");
    v.number(speed_max, "speed_max", TRange{0, 10, true, false, "m/s"},
             "each walker's speed is uniform in [min, max]");
    v.number(radius, "radius", TRange::closed(0.05, 2, "m"), "a walker's disc");
    v.number(period, "period", TRange{0, 1e6, true, false, "s"},
             "a new walker every period");
    v.number(phase, "phase", TRange::closed(0, 1e6, "s"), "time of the first walker");
    v.number(patience, "patience", TRange{0, 1e5, true, false, "s"},
             "a walker who cannot move at all for this long goes away");
}

void CAgentsSim::TWalker::validateRules() const {
    checkDistinctPoints(section, path);
    checkRule(speed_max >= speed_min, section, "speed_max", numberText(speed_max),
              "must be >= speed_min");
}

void CAgentsSim::TClutter::declare(Visitor& v) {
    v.requiredNumber(x, "x", kCoordinate, "centre x");
    v.requiredNumber(y, "y", kCoordinate, "centre y");
    v.number(radius, "radius", TRange::closed(0.02, 5, "m"), "the disc's radius");
}

void CAgentsSim::loadFromConfigFile(const mrpt::config::CConfigFileBase& c) {
    doors.clear();
    walkers.clear();
    clutter.clear();
    std::vector<std::string> secs;
    c.getAllSections(secs);
    std::sort(secs.begin(), secs.end());
    for (const auto& s : secs) {
        if (startsWithNumbered(s, "DoorPedestrian"))
            loadOptions(doors.emplace_back(), c, s);
        else if (startsWithNumbered(s, "CorridorWalker"))
            loadOptions(walkers.emplace_back(), c, s);
        else if (startsWithNumbered(s, "Clutter"))
            loadOptions(clutter.emplace_back(), c, s);
    }
}

void CAgentsSim::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    for (const auto& d : doors)
        d.saveToConfigFile(c, d.section);
    for (const auto& w : walkers)
        w.saveToConfigFile(c, w.section);
    for (const auto& k : clutter)
        k.saveToConfigFile(c, k.section);
}

void CAgentsSim::reset(uint64_t seed) {
    m_rng.seed(seed);
    m_active.clear();
    m_nextId = 0;
    m_names.clear();
    m_nextTime.assign(doors.size(), 0.0);
    m_nextSched.assign(doors.size(), 0);
    m_armed.assign(doors.size(), true);
    m_counts.assign(doors.size() + walkers.size(), 0);
    m_nextWalker.clear();
    for (const auto& w : walkers)
        m_nextWalker.push_back(w.phase);
    std::exponential_distribution<double> ex(1.0);
    for (size_t i = 0; i < doors.size(); i++)
        if (doors[i].emergence == "poisson")
            m_nextTime[i] = ex(m_rng) * 60.0 / doors[i].rate_per_min;
}

void CAgentsSim::spawn(double t, const std::string& kind, const std::string& source,
                       size_t srcIdx, int doorIndex, const std::vector<TPoint2D>& path,
                       double speed, double radius, double patience,
                       std::vector<TAgentEvent>& events) {
    TActive a;
    a.name = source + "#" + std::to_string(++m_counts[srcIdx]);
    a.source = source;
    a.path = &path;
    a.speed = speed;
    a.radius = radius;
    a.patience = patience;
    a.x = path.front().x;
    a.y = path.front().y;
    a.id = m_nextId++;
    m_names.push_back(a.name);
    a.doorIndex = doorIndex;
    m_active.push_back(a);
    events.push_back({t, kind, source, a.name, a.x, a.y});
}

void CAgentsSim::step(double t, double dt, const mrpt::math::TPose2D& robot,
                      double robotRadius, std::vector<TAgentEvent>& events) {
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::exponential_distribution<double> ex(1.0);
    auto doorBusy = [&](size_t i) {
        return std::any_of(m_active.begin(), m_active.end(),
                           [&](const TActive& a) { return a.doorIndex == int(i); });
    };
    // New people. One person per door at a time: a door does not emit a crowd.
    for (size_t i = 0; i < doors.size(); i++) {
        const auto& d = doors[i];
        bool go = false;
        if (d.emergence == "poisson") {
            if (t >= m_nextTime[i]) {
                go = !doorBusy(i);
                m_nextTime[i] = t + ex(m_rng) * 60.0 / d.rate_per_min;
            }
        } else if (d.emergence == "schedule") {
            if (m_nextSched[i] < d.schedule.size() && t >= d.schedule[m_nextSched[i]]) {
                go = !doorBusy(i);
                m_nextSched[i]++;
            }
        } else {
            const TPoint2D m = d.doorMid();
            const double dist = std::hypot(robot.x - m.x, robot.y - m.y);
            if (m_armed[i] && dist <= d.trigger_distance) {
                m_armed[i] = false;  // one draw per pass of the robot
                go = u01(m_rng) < d.trigger_probability && !doorBusy(i);
            } else if (!m_armed[i] && dist > d.trigger_distance + 1.0)
                m_armed[i] = true;
        }
        if (go)
            spawn(t, "emerge", d.section, i, int(i), d.path, d.speed, d.radius,
                  d.patience, events);
    }
    for (size_t k = 0; k < walkers.size(); k++) {
        const auto& w = walkers[k];
        if (t >= m_nextWalker[k]) {
            const double v = w.speed_min + (w.speed_max - w.speed_min) * u01(m_rng);
            spawn(t, "spawn", w.section, doors.size() + k, -1, w.path, v, w.radius,
                  w.patience, events);
            m_nextWalker[k] += w.period;
        }
    }
    // Move along the paths. A person heads for a point that runs along its
    // path and leads it by at most kLead (longer than the robot's diameter, so
    // the point gets past a robot standing on the path). A step that would
    // touch the robot slides along the robot's circle instead: people walk
    // around a robot, they do not walk into it. Only a person that cannot move
    // at all waits, and gives up after its patience.
    std::vector<TActive> keep;
    const double kLead = 2.0 * (robotRadius + 0.5) + 0.3;
    for (auto& a : m_active) {
        const auto& p = *a.path;
        // Advance the path point while it is close enough ahead.
        TPoint2D target;
        bool atEnd = false;
        auto locate = [&]() {
            size_t seg = a.seg;
            double along = a.along;
            while (true) {
                const double len =
                    std::hypot(p[seg + 1].x - p[seg].x, p[seg + 1].y - p[seg].y);
                if (along <= len) {
                    a.seg = seg;
                    a.along = along;
                    target = {p[seg].x + along / len * (p[seg + 1].x - p[seg].x),
                              p[seg].y + along / len * (p[seg + 1].y - p[seg].y)};
                    return;
                }
                along -= len;
                if (seg + 2 >= p.size()) {
                    a.seg = seg;
                    a.along = len;
                    target = p.back();
                    atEnd = true;
                    return;
                }
                seg++;
            }
        };
        locate();
        if (std::hypot(target.x - a.x, target.y - a.y) < kLead) {
            a.along += a.speed * dt;
            locate();
        }
        double mx = target.x - a.x, my = target.y - a.y;
        const double want = std::hypot(mx, my), maxStep = a.speed * dt;
        if (want > maxStep) {
            mx *= maxStep / want;
            my *= maxStep / want;
        }
        const double keepOut = a.radius + robotRadius + 0.05;
        const double rx = a.x - robot.x, ry = a.y - robot.y, rd = std::hypot(rx, ry);
        if (std::hypot(a.x + mx - robot.x, a.y + my - robot.y) < keepOut && rd > 1e-9) {
            const double ux = rx / rd, uy = ry / rd, inward = mx * ux + my * uy;
            double tx = mx - std::min(0.0, inward) * ux,
                   ty = my - std::min(0.0, inward) * uy;
            // Walking straight at the robot's centre leaves no tangential
            // component: step aside (to the left), as people do.
            if (std::hypot(tx, ty) < 1e-6 * maxStep) {
                tx = uy * maxStep;
                ty = -ux * maxStep;
            }
            const double tl = std::hypot(tx, ty);
            if (tl > 1e-9) {
                tx *= maxStep / tl;
                ty *= maxStep / tl;
            }
            mx = tx;
            my = ty;
            if (tl < 1e-9 || std::hypot(a.x + mx - robot.x, a.y + my - robot.y) <
                                 std::min(keepOut, rd) - 1e-6) {
                a.blocked += dt;
                if (a.blocked > a.patience) {
                    events.push_back({t, "give_up", a.source, a.name, a.x, a.y});
                    continue;
                }
                keep.push_back(a);
                continue;
            }
        }
        a.blocked = 0;
        a.x += mx;
        a.y += my;
        if (atEnd && std::hypot(target.x - a.x, target.y - a.y) < 0.05) {
            events.push_back({t, "leave", a.source, a.name, a.x, a.y});
            continue;
        }
        keep.push_back(a);
    }
    m_active.swap(keep);
}

const CAgentsSim::TClutter* CAgentsSim::clutterOverlapping(double x, double y,
                                                           double radius,
                                                           double* centreDistance) const {
    for (const auto& k : clutter) {
        const double d = std::hypot(k.x - x, k.y - y);
        if (d < k.radius + radius) {
            if (centreDistance)
                *centreDistance = d;
            return &k;
        }
    }
    return nullptr;
}

std::vector<TDisc> CAgentsSim::discs() const {
    std::vector<TDisc> d;
    d.reserve(m_active.size() + clutter.size());
    for (size_t i = 0; i < clutter.size(); i++)
        d.push_back({clutter[i].x, clutter[i].y, clutter[i].radius, -1 - int(i)});
    for (const auto& a : m_active)
        d.push_back({a.x, a.y, a.radius, a.id});
    return d;
}

}  // namespace risknav::sim
