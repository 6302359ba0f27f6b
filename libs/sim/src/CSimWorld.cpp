#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/sim/CSimWorld.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace risknav::common;
using mrpt::math::TPoint2D;

namespace risknav::sim {
namespace {
// Independent random streams per source, so that adding a sensor does not
// change the people's behaviour (and vice versa).
uint64_t streamSeed(uint64_t seed, uint64_t stream) {
    uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
}  // namespace

CSimWorld::CSimWorld() {
    range2.options.section = "RangeSensor2";
    range2.options.enabled = false;
    range2.options.label = "RANGE2";
    range2.options.fov_deg = 360;
    range2.options.beams = 72;
    range2.options.max_range = 5.0;
    range2.options.noise_std = 0.05;
    range2.options.dropout_probability = 0.2;
    range2.options.x = 0.0;
    range2.options.z = 0.5;
}

void CSimWorld::loadFromConfigFile(const mrpt::config::CConfigFileBase& c) {
    loadOptions(mapSource, c, "World");
    loadOptions(obstacleRule, c, "World");
    loadOptions(robot, c, "Robot");
    loadOptions(odometry.options, c, "Odometry");
    loadOptions(laser.options, c, "Laser");
    loadOptions(range2.options, c, "RangeSensor2");
    if (laser.options.frame_decimation != 1)
        throw CBadInputError(
            configWhere(c) +
            "[Laser] frame_decimation must be 1: the main laser defines the frames");
    if (!laser.options.enabled)
        throw CBadInputError(configWhere(c) +
                             "[Laser] enabled = false: the main laser defines the "
                             "frames and cannot be off");
    agents.loadFromConfigFile(c);
    m_grid = loadOccupancyGrid(mapSource);
    buildField();
}

void CSimWorld::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    mapSource.saveToConfigFile(c, "World");
    obstacleRule.saveToConfigFile(c, "World");
    robot.saveToConfigFile(c, "Robot");
    odometry.options.saveToConfigFile(c, "Odometry");
    laser.options.saveToConfigFile(c, "Laser");
    range2.options.saveToConfigFile(c, "RangeSensor2");
    agents.saveToConfigFile(c);
}

void CSimWorld::setMap(const mrpt::maps::COccupancyGridMap2D& grid) {
    obstacleRule.validate();
    robot.validate();
    odometry.options.validate();
    laser.options.validate();
    range2.options.validate();
    m_grid = grid;
    buildField();
}

void CSimWorld::buildField() {
    m_field = mapping::CDistanceField(m_grid, obstacleRule);
    if (m_field.freeCount() == 0)
        throw CBadInputError(mapSource.map_file + ": the map has no free cell");
    m_rayMap = CRayCastMap(m_grid, obstacleRule);
}

void CSimWorld::reset(const mrpt::math::TPose2D& start, uint64_t seed, double startTime) {
    m_vehicle = CDiffDriveVehicle();
    m_vehicle.setCurrentGTPose(start);
    odometry.reset(start, streamSeed(seed, 1));
    agents.reset(streamSeed(seed, 2));
    m_rngLaser.seed(streamSeed(seed, 3));
    m_rngRange2.seed(streamSeed(seed, 4));
    m_agentEvents.clear();
    m_v = m_w = m_vCmd = m_wCmd = 0;
    m_startTime = startTime;
    m_base = m_dt = 0;
    m_count = 0;
    m_senses = m_range2Scans = 0;
}

mrpt::Clock::time_point CSimWorld::timestamp() const {
    return mrpt::Clock::fromDouble(m_startTime + time());
}

void CSimWorld::command(double v, double w) {
    const double maxW = robot.max_w_deg * M_PI / 180.0;
    m_vCmd = std::clamp(v, -robot.max_v, robot.max_v);
    m_wCmd = std::clamp(w, -maxW, maxW);
}

void CSimWorld::step(double dt) {
    const double t0 = time();
    const double wAcc = robot.w_accel_deg * M_PI / 180.0;
    m_v += std::clamp(m_vCmd - m_v, -robot.decel * dt, robot.accel * dt);
    m_w += std::clamp(m_wCmd - m_w, -wAcc * dt, wAcc * dt);
    if (std::abs(m_v) < 1e-9)
        m_v = 0;
    if (std::abs(m_w) < 1e-9)
        m_w = 0;
    m_vehicle.advance(m_v, m_w, dt);
    const auto tw = m_vehicle.getCurrentGTVelLocal();
    odometry.step(tw.vx, tw.omega, dt);
    agents.step(t0 + dt, dt, truePose(), robot.radius, m_agentEvents);
    if (dt != m_dt) {  // a new step length: restart the count from here
        m_base = t0;
        m_dt = dt;
        m_count = 0;
    }
    m_count++;
}

CSimWorld::TScans CSimWorld::sense() {
    const auto ts = timestamp();
    const auto gt = truePose();
    const auto discs = agents.discs();
    TScans s;
    s.laser = laser.simulate(m_rayMap, gt, discs, ts, m_rngLaser);
    if (range2.options.enabled &&
        m_senses % size_t(range2.options.frame_decimation) == 0) {
        s.range2 = range2.simulate(m_rayMap, gt, discs, ts, m_rngRange2);
        m_range2Scans++;
    }
    m_senses++;
    return s;
}

double CSimWorld::rangesPerFrame() const {
    const auto& r2 = range2.options;
    return double(laser.options.beams) +
           (r2.enabled ? double(r2.beams) / std::max(1, r2.frame_decimation) : 0.0);
}

bool CSimWorld::onMap(double x, double y) const {
    return x >= m_grid.getXMin() && x <= m_grid.getXMax() && y >= m_grid.getYMin() &&
           y <= m_grid.getYMax();
}

CSimWorld::TPlacement CSimWorld::placement(double x, double y) const {
    char b[240];
    if (!onMap(x, y))
        return {"the map", "is outside the map"};
    const double R = robot.radius, cl = pointClearance(x, y);
    if (cl < R) {
        std::snprintf(b, sizeof(b),
                      "is inside an obstacle (clearance %.2f m < robot radius %.2f m)",
                      cl, R);
        return {"the map", b};
    }
    double d = 0;
    if (const auto* k = agents.clutterOverlapping(x, y, R, &d)) {
        std::snprintf(b, sizeof(b),
                      "is inside [%s] (%.2f m from its centre < %.2f m + robot radius "
                      "%.2f m)",
                      k->section.c_str(), d, k->radius, R);
        return {"[" + k->section + "]", b};
    }
    return {};
}

std::optional<TPoint2D> CSimWorld::firstSampleWhere(
    const TPoint2D& a, const TPoint2D& b,
    const std::function<bool(const TPoint2D&)>& bad) const {
    const double step = 0.5 * m_grid.getResolution();
    const int n = std::max(1, int(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / step)));
    for (int k = 0; k <= n; k++) {
        const TPoint2D q(a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n);
        if (bad(q))
            return q;
    }
    return std::nullopt;
}

void CSimWorld::checkAgentsAgainstMap(const mrpt::config::CConfigFileBase& c) const {
    auto where = [](const TPoint2D& p) { return pointText(p.x, p.y); };
    // People walk where the map is free: a lane inside or through a wall (a
    // walker at y = 0.1 in the outer wall, a pedestrian path across the
    // corridor's walls) is refused rather than taken in silence.
    auto checkPath = [&](const std::string& sec, const std::vector<TPoint2D>& p) {
        const std::string text = readString(c, sec, "path", "");
        for (const auto& q : p)
            if (!onMap(q.x, q.y))
                throwBadKey(c, sec, "path", text,
                            "point " + where(q) + " is outside the map");
        // its centre on a map obstacle (the datasets' lanes pass end walls and
        // corners 0.2 m off, less than a person's radius: people brush past
        // walls, they do not walk through them)
        for (size_t i = 1; i < p.size(); i++)
            if (const auto q = firstSampleWhere(p[i - 1], p[i], [&](const TPoint2D& r) {
                    return clearance(r.x, r.y) <= 0;
                }))
                throwBadKey(c, sec, "path", text,
                            "segment " + std::to_string(i) +
                                " runs through an obstacle of the map at " + where(*q));
    };
    for (const auto& d : agents.doors) {
        checkPath(d.section, d.path);
        for (const TPoint2D q :
             {TPoint2D(d.door[0], d.door[1]), TPoint2D(d.door[2], d.door[3])})
            if (!onMap(q.x, q.y))
                throwBadKey(c, d.section, "door", readString(c, d.section, "door", ""),
                            "point " + where(q) + " is outside the map");
    }
    for (const auto& w : agents.walkers)
        checkPath(w.section, w.path);
    for (const auto& k : agents.clutter) {
        if (!onMap(k.x, k.y))
            throw CBadInputError(configWhere(c) + "[" + k.section +
                                 "] x, y: outside the map");
        if (clearance(k.x, k.y) <= 0)
            throw CBadInputError(configWhere(c) + "[" + k.section +
                                 "] x, y: " + where({k.x, k.y}) +
                                 " lies inside an obstacle of the map (clutter is what "
                                 "the map does not hold)");
    }
}

}  // namespace risknav::sim
