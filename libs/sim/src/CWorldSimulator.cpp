#include <risknav/common/CBadInputError.h>
#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/CProgress.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/common/summary_json.h>
#include <risknav/sim/CRawlogWriter.h>
#include <risknav/sim/CWorldSimulator.h>

#include <mrpt/kinematics/CVehicleSimul_DiffDriven.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>

#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
using nlohmann::json;

namespace risknav::sim {
void CWorldSimulator::TSimulationOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s) {
    sim_dt = readDouble(c, s, "sim_dt", sim_dt, TRange::closed(0.001, 0.5, "s"));
    frame_rate_hz =
        readDouble(c, s, "frame_rate_hz", frame_rate_hz, TRange::closed(0.1, 100, "Hz"));
    duration_max =
        readDouble(c, s, "duration_max", duration_max, TRange::closed(1, 1e6, "s"));
    seed = static_cast<uint64_t>(
        readDouble(c, s, "seed", double(seed), TRange::closed(0, 9007199254740992.0)));
    start_time = readDouble(c, s, "start_time", start_time, TRange::closed(0, 4e9, "s"));
    obstacle_threshold = readDouble(c, s, "obstacle_threshold", obstacle_threshold,
                                    TRange::closed(0.01, 0.99));
}

void CWorldSimulator::TSimulationOptions::validate() const {
    const double ratio = 1.0 / (frame_rate_hz * sim_dt);
    if (std::abs(ratio - std::round(ratio)) > 1e-6)
        throw CConfigKeyError(
            "Simulation", "sim_dt", std::to_string(sim_dt),
            "the frame period 1/frame_rate_hz must be a whole multiple of sim_dt");
}

void CWorldSimulator::TRobotOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s) {
    radius = readDouble(c, s, "radius", radius, TRange::closed(0.05, 2, "m"));
    max_v = readDouble(c, s, "max_v", max_v, {0, 5, true, false, "m/s"});
    max_w_deg = readDouble(c, s, "max_w_deg", max_w_deg, {0, 720, true, false, "deg/s"});
    accel = readDouble(c, s, "accel", accel, {0, 20, true, false, "m/s^2"});
    decel = readDouble(c, s, "decel", decel, {0, 20, true, false, "m/s^2"});
    w_accel_deg =
        readDouble(c, s, "w_accel_deg", w_accel_deg, {0, 10000, true, false, "deg/s^2"});
    stop_enabled = readBool(c, s, "stop_enabled", stop_enabled);
    stop_t_delay =
        readDouble(c, s, "stop_t_delay", stop_t_delay, TRange::closed(0, 10, "s"));
    stop_margin =
        readDouble(c, s, "stop_margin", stop_margin, TRange::closed(0, 10, "m"));
    lateral_margin =
        readDouble(c, s, "lateral_margin", lateral_margin, TRange::closed(0, 2, "m"));
    near_miss_distance = readDouble(c, s, "near_miss_distance", near_miss_distance,
                                    TRange::closed(0, 5, "m"));
}

CWorldSimulator::CWorldSimulator() {
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

double CWorldSimulator::clearance(double x, double y) const {
    const int cx = m_grid.x2idx(x), cy = m_grid.y2idx(y);
    if (cx < 0 || cy < 0 || cx >= m_clearance.cols || cy >= m_clearance.rows)
        return 0.0;
    return m_clearance.at<float>(cy, cx);
}

void CWorldSimulator::loadFromConfigFile(const CIniConfig& c,
                                         std::optional<uint64_t> seedOverride) {
    static const std::set<std::string> known = {
        "Simulation", "World", "Robot", "Odometry", "Route", "Laser", "RangeSensor2"};
    for (const auto& s : c.sections())
        if (!known.count(s) && !CAgentsSim::ownsSection(s))
            throw CBadInputError(c.path() + ": unknown section [" + s +
                                 "] (known: Simulation, World, Robot, Odometry, Route, "
                                 "Laser, RangeSensor2, "
                                 "DoorPedestrianN, CorridorWalkerN, ClutterN)");
    if (!c.sectionExists("World"))
        throw CBadInputError(c.path() + ": missing section [World] (map_file)");
    if (!c.sectionExists("Route"))
        throw CBadInputError(c.path() + ": missing section [Route] (waypoints)");
    loadOptions(simulation, c, "Simulation");
    if (seedOverride) {
        simulation.seed = *seedOverride;
        c.recordEffective("Simulation", "seed", std::to_string(simulation.seed));
    }
    loadOptions(world, c, "World");
    loadOptions(robot, c, "Robot");
    loadOptions(odometry.options, c, "Odometry");
    loadOptions(route.options, c, "Route");
    loadOptions(laser.options, c, "Laser");
    loadOptions(range2.options, c, "RangeSensor2");
    if (laser.options.frame_decimation != 1)
        throw CBadInputError(
            c.path() +
            ": [Laser] frame_decimation must be 1: the main laser defines the frames");
    if (!laser.options.enabled)
        throw CBadInputError(c.path() +
                             ": [Laser] enabled = false: the main laser defines the "
                             "frames and cannot be off");
    agents.loadFromConfigFile(c);
    c.throwOnUnreadKeys();

    m_grid = loadOccupancyGrid(world);
    // Clearance map: Euclidean distance to the nearest obstacle cell.
    const int nx = int(m_grid.getSizeX()), ny = int(m_grid.getSizeY());
    cv::Mat freeMask(ny, nx, CV_8UC1);
    size_t nFree = 0;
    for (int cy = 0; cy < ny; cy++)
        for (int cx = 0; cx < nx; cx++) {
            const bool fr = m_grid.getCell(cx, cy) >= simulation.obstacle_threshold;
            freeMask.at<uint8_t>(cy, cx) = fr ? 255 : 0;
            nFree += fr;
        }
    if (nFree == 0)
        throw CBadInputError(world.map_file + ": the map has no free cell");
    cv::distanceTransform(freeMask, m_clearance, cv::DIST_L2, cv::DIST_MASK_PRECISE,
                          CV_32F);
    m_clearance *= m_grid.getResolution();
    checkAgainstMap(c);
}

void CWorldSimulator::checkAgainstMap(const CIniConfig& c) const {
    auto where = [](const TPoint2D& p) {
        char b[64];
        std::snprintf(b, sizeof(b), "(%.2f, %.2f)", p.x, p.y);
        return std::string(b);
    };
    auto onMap = [&](const TPoint2D& p) {
        return p.x >= m_grid.getXMin() && p.x <= m_grid.getXMax() &&
               p.y >= m_grid.getYMin() && p.y <= m_grid.getYMax();
    };
    const auto wps = route.waypoints();
    const std::string wpText = readString(c, "Route", "waypoints", "");
    for (const auto& p : wps)
        if (!onMap(p))
            throwBadKey(c, "Route", "waypoints", wpText,
                        "point " + where(p) + " is outside the map");
    const double R = robot.radius;
    if (clearance(wps[0].x, wps[0].y) < R) {
        char b[160];
        std::snprintf(
            b, sizeof(b),
            "start %s is inside an obstacle (clearance %.2f m < robot radius %.2f m)",
            where(wps[0]).c_str(), clearance(wps[0].x, wps[0].y), R);
        throwBadKey(c, "Route", "waypoints", wpText, b);
    }
    std::vector<TPoint2D> pass = wps;
    if (route.options.mode == "loop")
        pass.push_back(wps.front());
    const double step = 0.5 * m_grid.getResolution();
    for (size_t i = 1; i < pass.size(); i++) {
        const double L = std::hypot(pass[i].x - pass[i - 1].x, pass[i].y - pass[i - 1].y);
        const int n = std::max(1, int(std::ceil(L / step)));
        for (int k = 0; k <= n; k++) {
            const TPoint2D q(pass[i - 1].x + (pass[i].x - pass[i - 1].x) * k / n,
                             pass[i - 1].y + (pass[i].y - pass[i - 1].y) * k / n);
            const double cl = clearance(q.x, q.y);
            if (cl < R) {
                char b[220];
                std::snprintf(b, sizeof(b),
                              "segment %zu %s -> %s runs through an obstacle at %s "
                              "(clearance %.2f m < "
                              "robot radius %.2f m)",
                              i, where(pass[i - 1]).c_str(), where(pass[i]).c_str(),
                              where(q).c_str(), cl, R);
                throwBadKey(c, "Route", "waypoints", wpText, b);
            }
        }
    }
    auto checkPath = [&](const std::string& sec, const std::vector<TPoint2D>& p) {
        for (const auto& q : p)
            if (!onMap(q))
                throwBadKey(c, sec, "path", readString(c, sec, "path", ""),
                            "point " + where(q) + " is outside the map");
    };
    for (const auto& d : agents.doors)
        checkPath(d.section, d.path);
    for (const auto& w : agents.walkers)
        checkPath(w.section, w.path);
    for (const auto& k : agents.clutter)
        if (!onMap({k.x, k.y}))
            throw CBadInputError(c.path() + ": [" + k.section +
                                 "] x, y: outside the map");
}

namespace {
// Independent random streams per source, so that adding a sensor does not
// change the people's behaviour (and vice versa).
uint64_t streamSeed(uint64_t seed, uint64_t stream) {
    uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

struct TSafetyEvent {
    double t;
    std::string kind, object;
    double rx, ry, ox, oy, gap;
};

std::string num(double v) {
    return CCsvWriter::num(v, 9);
}

void writePoseLine(std::ofstream& f, double t, const TPose2D& p) {
    char b[128];
    std::snprintf(b, sizeof(b), "%.3f %.6f %.6f %.6f\n", t, p.x, p.y, p.phi);
    f << b;
}
}  // namespace

json CWorldSimulator::run(COutputDir& out, bool quiet) {
    const auto wall0 = std::chrono::steady_clock::now();
    const double dt = simulation.sim_dt;
    const int stepsPerFrame = int(std::lround(1.0 / (simulation.frame_rate_hz * dt)));
    const double maxW = robot.max_w_deg * M_PI / 180.0,
                 wAcc = robot.w_accel_deg * M_PI / 180.0;

    route.reset();
    const TPose2D start = route.startPose();
    mrpt::kinematics::CVehicleSimul_DiffDriven vehicle;
    vehicle.setCurrentGTPose(start);
    odometry.reset(start, streamSeed(simulation.seed, 1));
    agents.reset(streamSeed(simulation.seed, 2));
    std::mt19937_64 rngLaser(streamSeed(simulation.seed, 3)),
        rngRange2(streamSeed(simulation.seed, 4));

    CRawlogWriter rawlog(out.stage("simulation.rawlog"));
    std::ofstream gtFile(out.stage("groundtruth.txt")),
        odoFile(out.stage("odometry.txt"));
    gtFile << "% t x y phi  (ground truth at each frame; t = UNIX time [s], phi [rad])\n";
    odoFile << "% t x y phi  (odometry at each frame, as logged in the rawlog)\n";

    double estDuration = 0;
    for (size_t i = 1; i < route.points().size(); i++)
        estDuration += std::hypot(route.points()[i].x - route.points()[i - 1].x,
                                  route.points()[i].y - route.points()[i - 1].y) /
                       std::min(robot.max_v, route.legSpeeds()[i]);
    const size_t estFrames =
        size_t(std::min(simulation.duration_max, 1.1 * estDuration + 10) *
               simulation.frame_rate_hz);
    CProgress progress("simulate", estFrames, "frames", quiet);

    std::vector<TAgentEvent> agentEvents;
    std::vector<TSafetyEvent> safety;
    std::vector<TPoint2D> gtTrack, odoTrack;
    std::map<int, int> contactState;  // object id -> 0 clear, 1 near, 2 collision
    int staticState = 0;
    double minGapAgents = std::numeric_limits<double>::infinity();
    double minGapStatic = std::numeric_limits<double>::infinity();
    double v = 0, w = 0, distance = 0, stoppedTime = 0;
    int stops = 0, collisions = 0, collisionsStatic = 0, nearMisses = 0;
    bool blockedPrev = false, timeout = false;
    size_t range2Scans = 0;
    mrpt::obs::CObservation2DRangeScan::Ptr lastScan;
    TPose2D lastOdo = odometry.pose();
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions
        motionOpts;  // MRPT's default Gaussian model

    for (long k = 0;; k++) {
        const double t = k * dt;
        const TPose2D gt = vehicle.getCurrentGTPose();
        if (k % stepsPerFrame == 0) {
            const auto ts = mrpt::Clock::fromDouble(simulation.start_time + t);
            const size_t frame = rawlog.frames();
            const auto discs = agents.discs();
            mrpt::obs::CSensoryFrame sf;
            lastScan = laser.simulate(m_grid, gt, discs, ts, rngLaser);
            sf.insert(lastScan);
            if (range2.options.enabled &&
                frame % size_t(range2.options.frame_decimation) == 0) {
                sf.insert(range2.simulate(m_grid, gt, discs, ts, rngRange2));
                range2Scans++;
            }
            mrpt::obs::CActionCollection acts;
            mrpt::obs::CActionRobotMovement2D mv;
            mv.timestamp = ts;
            mv.computeFromOdometry(
                mrpt::poses::CPose2D(odometry.pose()) - mrpt::poses::CPose2D(lastOdo),
                motionOpts);
            acts.insert(mv);
            rawlog.write(acts, sf);
            lastOdo = odometry.pose();
            writePoseLine(gtFile, simulation.start_time + t, gt);
            writePoseLine(odoFile, simulation.start_time + t, odometry.pose());
            gtTrack.emplace_back(gt.x, gt.y);
            odoTrack.emplace_back(odometry.pose().x, odometry.pose().y);
            progress.update(rawlog.frames());
            if (route.finished() && std::abs(v) < 1e-9 && std::abs(w) < 1e-9)
                break;
            if (t >= simulation.duration_max) {
                timeout = true;
                break;
            }
        }

        // Control: route, then the stopping-distance rule on the latest scan.
        double vDes = 0, wDes = 0;
        route.compute(gt, maxW, robot.decel, vDes, wDes);
        vDes = std::min(vDes, robot.max_v);
        bool blocked = false;
        if (robot.stop_enabled && vDes > 0 && lastScan) {
            const double reach = stoppingDistance(vDes, robot.stop_t_delay, robot.decel) +
                                 robot.stop_margin;
            const double halfW = robot.radius + robot.lateral_margin;
            const auto& so = laser.options;
            const size_t n = lastScan->getScanSize();
            const double a0 = -0.5 * lastScan->aperture,
                         da = n > 1 ? lastScan->aperture / (n - 1) : 0.0;
            const double syaw = so.yaw_deg * M_PI / 180.0;
            for (size_t i = 0; i < n && !blocked; i++) {
                if (!lastScan->getScanRangeValidity(i))
                    continue;
                const double r = lastScan->getScanRange(i), a = syaw + a0 + da * i;
                const double px = so.x + r * std::cos(a), py = so.y + r * std::sin(a);
                blocked = px > 0 && std::abs(py) <= halfW && px - robot.radius < reach;
            }
        }
        if (blocked) {
            // Stop, but keep turning in place: a robot stopped askew in a doorway
            // would otherwise stay blocked by the door jamb forever.
            vDes = 0;
            stoppedTime += dt;
            if (!blockedPrev)
                stops++;
        }
        blockedPrev = blocked;
        v += std::clamp(vDes - v, -robot.decel * dt, robot.accel * dt);
        w += std::clamp(wDes - w, -wAcc * dt, wAcc * dt);
        if (std::abs(v) < 1e-9)
            v = 0;
        if (std::abs(w) < 1e-9)
            w = 0;
        vehicle.movementCommand(v, w);
        vehicle.simulateOneTimeStep(dt);
        const auto tw = vehicle.getCurrentGTVelLocal();
        odometry.step(tw.vx, tw.omega, dt);
        const TPose2D now = vehicle.getCurrentGTPose();
        distance += std::hypot(now.x - gt.x, now.y - gt.y);
        agents.step(t + dt, dt, now, robot.radius, agentEvents);

        // Safety bookkeeping: collisions and near misses, one event per episode.
        for (const auto& d : agents.discs()) {
            const double gap = std::hypot(d.x - now.x, d.y - now.y) - d.r - robot.radius;
            minGapAgents = std::min(minGapAgents, gap);
            int& st = contactState[d.objectId];
            const int nst = gap < 0 ? 2 : (gap < robot.near_miss_distance ? 1 : 0);
            if (nst > st) {
                const std::string obj =
                    d.objectId < 0 ? agents.clutter[size_t(-1 - d.objectId)].section
                                   : agents.agentName(d.objectId);
                safety.push_back({t + dt, nst == 2 ? "collision" : "near_miss", obj,
                                  now.x, now.y, d.x, d.y, gap});
                (nst == 2 ? collisions : nearMisses)++;
            }
            if (nst > st || gap > robot.near_miss_distance + 0.05)
                st = nst;
        }
        const double gapStatic = clearance(now.x, now.y) - robot.radius;
        minGapStatic = std::min(minGapStatic, gapStatic);
        if (gapStatic < 0 && staticState == 0) {
            safety.push_back(
                {t + dt, "collision", "map", now.x, now.y, now.x, now.y, gapStatic});
            collisionsStatic++;
        }
        staticState = gapStatic < 0;
    }
    rawlog.close();
    gtFile.close();
    odoFile.close();
    if (!gtFile || !odoFile)
        throw std::runtime_error("cannot write groundtruth.txt / odometry.txt");
    progress.finish();

    const double duration = (rawlog.frames() - 1) / simulation.frame_rate_hz;
    {
        CCsvWriter csv(out.stage("agent_events.csv"),
                       {"t", "kind", "source", "agent", "x", "y"});
        for (const auto& e : agentEvents)
            csv.row({CCsvWriter::fixed(simulation.start_time + e.t, 3), e.kind, e.source,
                     e.agent, num(e.x), num(e.y)});
        csv.close();
    }
    {
        CCsvWriter csv(
            out.stage("safety_events.csv"),
            {"t", "kind", "object", "robot_x", "robot_y", "object_x", "object_y", "gap"});
        for (const auto& e : safety)
            csv.row({CCsvWriter::fixed(simulation.start_time + e.t, 3), e.kind, e.object,
                     num(e.rx), num(e.ry), num(e.ox), num(e.oy), num(e.gap)});
        csv.close();
    }
    saveGridmapGz(m_grid, out.stage("map.gridmap.gz"));

    size_t emergences = 0, spawned = 0, gaveUp = 0;
    for (const auto& e : agentEvents) {
        emergences += e.kind == "emerge";
        spawned += e.kind == "spawn";
        gaveUp += e.kind == "give_up";
    }
    const TPose2D endGt = vehicle.getCurrentGTPose(), endOdo = odometry.pose();
    const double odoErr = std::hypot(endGt.x - endOdo.x, endGt.y - endOdo.y);

    // The picture.
    {
        CMapImage img(m_grid);
        img.polyline(route.waypoints(), {190, 190, 190}, 6);
        for (const auto& wk : agents.walkers)
            img.polyline(wk.path, {150, 110, 200}, 1, true);
        for (const auto& d : agents.doors) {
            img.polyline(d.path, {240, 190, 120}, 1, true);
            img.segment({d.door[0], d.door[1]}, {d.door[2], d.door[3]}, {230, 120, 0}, 5);
            img.text({d.door[2] + 0.1, d.door[3] + 0.1}, d.section, {160, 80, 0}, 0.4);
        }
        for (const auto& k : agents.clutter)
            img.circle({k.x, k.y}, k.radius, {140, 90, 40}, 1, true);
        img.polyline(odoTrack, {120, 120, 120}, 1, true);
        img.polyline(gtTrack, {0, 90, 200}, 2);
        for (const auto& e : agentEvents)
            if (e.kind == "emerge")
                img.marker({e.x, e.y}, CMapImage::TMarker::Triangle, {230, 120, 0}, 10,
                           2);
        for (const auto& e : safety)
            img.marker({e.ox, e.oy},
                       e.kind == "collision" ? CMapImage::TMarker::Cross
                                             : CMapImage::TMarker::Circle,
                       e.kind == "collision" ? TRgb{220, 0, 0} : TRgb{200, 0, 200}, 12,
                       2);
        img.marker({start.x, start.y}, CMapImage::TMarker::Square, {0, 160, 0}, 14, 2);
        img.marker({endGt.x, endGt.y}, CMapImage::TMarker::Star, {0, 0, 0}, 14, 2);
        img.legendLine("route", {190, 190, 190}, 6);
        img.legendLine("true path", {0, 90, 200}, 2);
        img.legendLine("odometry", {120, 120, 120}, 1);
        if (!agents.doors.empty())
            img.legendLine("door", {230, 120, 0}, 5);
        if (!agents.walkers.empty())
            img.legendLine("walker lane", {150, 110, 200}, 1);
        if (emergences)
            img.legendMarker("person emerged", CMapImage::TMarker::Triangle,
                             {230, 120, 0});
        if (collisions + collisionsStatic)
            img.legendMarker("collision", CMapImage::TMarker::Cross, {220, 0, 0});
        if (nearMisses)
            img.legendMarker("near miss", CMapImage::TMarker::Circle, {200, 0, 200});
        img.legendMarker("start", CMapImage::TMarker::Square, {0, 160, 0});
        img.legendMarker("end", CMapImage::TMarker::Star, {0, 0, 0});
        char title[256];
        std::snprintf(title, sizeof(title),
                      "risknav-simulate: %s  |  %.0f s, %.1f m, %zu frames, %d "
                      "collisions, %d near misses",
                      std::filesystem::path(world.map_file).filename().c_str(), duration,
                      distance, rawlog.frames(), collisions + collisionsStatic,
                      nearMisses);
        img.setTitle(title);
        img.save(out.stage("world.png"));
    }

    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    auto finiteOrNull = [](double x) {
        return std::isfinite(x) ? json(x) : json(nullptr);
    };
    json j;
    j["status"] = timeout ? "timeout" : "completed";
    j["frames"] = rawlog.frames();
    j["duration_s"] = duration;
    j["distance_m"] = distance;
    j["route_length_m"] = route.length();
    j["laps"] = route.options.laps;
    j["collisions"] = collisions + collisionsStatic;
    j["collisions_static"] = collisionsStatic;
    j["near_misses"] = nearMisses;
    j["min_clearance_agents_m"] = finiteOrNull(minGapAgents);
    j["min_clearance_static_m"] = finiteOrNull(minGapStatic);
    j["emergences"] = emergences;
    j["walkers_spawned"] = spawned;
    j["agents_gave_up"] = gaveUp;
    j["stops"] = stops;
    j["stopped_time_s"] = stoppedTime;
    j["start_pose"] = {start.x, start.y, start.phi * 180 / M_PI};
    j["end_pose"] = {endGt.x, endGt.y, endGt.phi * 180 / M_PI};
    j["odometry"] = {{"error_model", odometry.options.error_model},
                     {"final_position_error_m", odoErr},
                     {"final_heading_error_deg",
                      mrpt::math::wrapToPi(endOdo.phi - endGt.phi) * 180 / M_PI},
                     {"true_wheel_geometry",
                      {{"radius_l", odometry.trueGeometry().radiusL},
                       {"radius_r", odometry.trueGeometry().radiusR},
                       {"tread", odometry.trueGeometry().tread}}}};
    j["map"] = {
        {"file", world.map_file},
        {"size_x", m_grid.getSizeX()},
        {"size_y", m_grid.getSizeY()},
        {"resolution", m_grid.getResolution()},
        {"bounds",
         {m_grid.getXMin(), m_grid.getXMax(), m_grid.getYMin(), m_grid.getYMax()}}};
    json sensors = json::array();
    sensors.push_back({{"label", laser.options.label},
                       {"beams", laser.options.beams},
                       {"fov_deg", laser.options.fov_deg},
                       {"max_range", laser.options.max_range},
                       {"scans", rawlog.frames()}});
    if (range2.options.enabled)
        sensors.push_back({{"label", range2.options.label},
                           {"beams", range2.options.beams},
                           {"fov_deg", range2.options.fov_deg},
                           {"max_range", range2.options.max_range},
                           {"scans", range2Scans}});
    j["sensors"] = sensors;
    j["outputs"] = out.stagedNames();
    j["timing"] = {{"wall_time_s", wall},
                   {"realtime_factor", wall > 0 ? duration / wall : 0.0}};
    return j;
}

void runSimulateApp(const TAppContext& ctx) {
    CWorldSimulator sim;
    sim.loadFromConfigFile(ctx.cfg, ctx.args.seed);
    COutputDir out(ctx.args.outDir);
    json summary = summaryHeader(ctx, sim.simulation.seed);
    summary.update(sim.run(out, ctx.args.quiet));
    out.writeText("config_effective.ini", ctx.cfg.effectiveConfigText());
    summary["outputs"].push_back("config_effective.ini");
    summary["outputs"].push_back("summary.json");
    out.writeText("summary.json", jsonText(summary));
    out.commit();
    if (!ctx.args.quiet)
        std::fprintf(stderr,
                     "%s: %s, %zu frames, %.0f s simulated, %d collisions -> %s\n",
                     ctx.info.name.c_str(), summary["status"].get<std::string>().c_str(),
                     summary["frames"].get<size_t>(), summary["duration_s"].get<double>(),
                     summary["collisions"].get<int>(), out.dir().c_str());
}

}  // namespace risknav::sim
