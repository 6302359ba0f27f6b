#include <risknav/common/CBadInputError.h>
#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CMapImage.h>
#include <risknav/common/CProgress.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/common/summary_json.h>
#include <risknav/sim/CClosedLoop.h>
#include <risknav/sim/CRawlogWriter.h>
#include <risknav/sim/CWorldSimulator.h>

#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using mrpt::math::TPose2D;
using nlohmann::json;

namespace risknav::sim {
void CWorldSimulator::TSimulationOptions::declare(Visitor& v) {
    v.number(sim_dt, "sim_dt", TRange::closed(0.001, 0.5, "s"),
             "physics and control step");
    v.number(
        frame_rate_hz, "frame_rate_hz", TRange::closed(0.1, 100, "Hz"),
        "one rawlog frame (odometry + scans) per period, a whole multiple of sim_dt");
    v.number(duration_max, "duration_max", TRange::closed(1, 1e6, "s"),
             "the run stops (status \"timeout\") if the route is not done");
    v.seed(seed, "seed", "people, sensor noise, odometry errors (--seed overrides)");
    v.number(start_time, "start_time", TRange::closed(0, 4e9, "s"),
             "UNIX time of the first frame (reproducible logs)");
    v.number(near_miss_distance, "near_miss_distance", TRange::closed(0, 5, "m"),
             "a gap (robot edge to person edge) below this is a near miss");
    v.number(relevance_beta, "relevance_beta", TRange::closed(0, 10, "m"),
             "a door pedestrian within d_stop(v) + this ahead of the front is logged "
             "(enter_corridor)");
    v.number(relevance_lateral_margin, "relevance_lateral_margin",
             TRange::closed(0, 5, "m"),
             "... and within the robot's radius + this to each side of it");
}

void CWorldSimulator::TSimulationOptions::validateRules() const {
    const double ratio = 1.0 / (frame_rate_hz * sim_dt);
    checkRule(std::abs(ratio - std::round(ratio)) <= 1e-6, section, "sim_dt",
              numberText(sim_dt),
              "the frame period 1/frame_rate_hz must be a whole multiple of sim_dt");
}

void CWorldSimulator::loadFromConfigFile(const CIniConfig& c,
                                         std::optional<uint64_t> seedOverride) {
    static const std::set<std::string> known = {"Simulation", "World",
                                                "Robot",      "Odometry",
                                                "Route",      "CStoppingDistanceLimiter",
                                                "Laser",      "RangeSensor2"};
    for (const auto& s : c.sections())
        if (!known.count(s) && !CAgentsSim::ownsSection(s))
            c.throwUnknownSection(s,
                                  "Simulation, World, Robot, Odometry, Route, "
                                  "CStoppingDistanceLimiter, Laser, RangeSensor2, "
                                  "DoorPedestrianN, CorridorWalkerN, ClutterN");
    if (!c.sectionExists("World"))
        throw CBadInputError(c.path() + ": missing section [World] (map_file)");
    if (!c.sectionExists("Route"))
        throw CBadInputError(c.path() + ": missing section [Route] (waypoints)");
    loadOptions(simulation, c, "Simulation");
    if (seedOverride)
        simulation.seed = *seedOverride;
    loadOptions(route.options, c, "Route");
    loadOptions(stopRule.options, c, "CStoppingDistanceLimiter");
    world.loadFromConfigFile(c);
    c.throwOnUnreadKeys();
    // The run's work and output, bounded before it starts: a robot that never
    // finishes its route runs to duration_max (sim_dt 0.01 s, 100 Hz frames of
    // 1081 beams over 1e6 s wrote 1.6 GB in 3 minutes, on its way to 400 GB)
    const auto& sim = simulation;
    const double steps = sim.duration_max / sim.sim_dt,
                 frames = sim.duration_max * sim.frame_rate_hz;
    const double rays = world.rangesPerFrame();
    const std::string dm =
        readString(c, "Simulation", "duration_max", numberText(sim.duration_max));
    if (steps > 2e7 * (1 + 1e-9))
        throwBadKey(c, "Simulation", "duration_max", dm,
                    "is " + numberText(std::round(steps)) +
                        " steps of sim_dt = " + numberText(sim.sim_dt) +
                        " s, at most 2e+07 (lower duration_max or raise sim_dt)");
    if (frames * rays > 5e8 * (1 + 1e-9))
        throwBadKey(c, "Simulation", "duration_max", dm,
                    "is " + numberText(std::round(frames)) + " frames of " +
                        numberText(std::round(rays)) +
                        " ranges, at most 5e+08 ranges in all (~2 GB of rawlog; lower "
                        "duration_max or frame_rate_hz)");
    checkAgainstMap(c);
}

void CWorldSimulator::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    simulation.saveToConfigFile(c, "Simulation");
    world.saveToConfigFile(c);
    route.options.saveToConfigFile(c, "Route");
    stopRule.options.saveToConfigFile(c, "CStoppingDistanceLimiter");
}

void CWorldSimulator::checkAgainstMap(const CIniConfig& c) const {
    auto where = [](const TPoint2D& p) { return pointText(p.x, p.y); };
    const auto wps = route.waypoints();
    const std::string wpText = readString(c, "Route", "waypoints", "");
    for (const auto& p : wps)
        if (!world.onMap(p.x, p.y))
            throwBadKey(c, "Route", "waypoints", wpText,
                        "point " + where(p) + " is outside the map");
    // the start in metres, as every app checks it (CSimWorld::placement())
    if (const auto pl = world.placement(wps[0].x, wps[0].y); !pl.free())
        throwBadKey(c, "Route", "waypoints", wpText,
                    "start " + where(wps[0]) + " " + pl.why);
    const double R = world.robot.radius;
    std::vector<TPoint2D> pass = wps;
    if (route.options.mode == "loop")
        pass.push_back(wps.front());
    for (size_t i = 1; i < pass.size(); i++)
        if (const auto q = world.firstSampleWhere(
                pass[i - 1], pass[i],
                [&](const TPoint2D& p) { return world.pointClearance(p.x, p.y) < R; })) {
            char b[220];
            std::snprintf(b, sizeof(b),
                          "segment %zu %s -> %s runs through an obstacle at %s "
                          "(clearance %.2f m < robot radius %.2f m)",
                          i, where(pass[i - 1]).c_str(), where(pass[i]).c_str(),
                          where(*q).c_str(), world.pointClearance(q->x, q->y), R);
            throwBadKey(c, "Route", "waypoints", wpText, b);
        }
    {
        double length = 0;
        for (size_t i = 1; i < pass.size(); i++)
            length += std::hypot(pass[i].x - pass[i - 1].x, pass[i].y - pass[i - 1].y);
        if (length < 1e-6)
            throwBadKey(c, "Route", "waypoints", wpText,
                        "the route has no length (every waypoint is the start)");
    }
    world.checkAgentsAgainstMap(c);
}

namespace {
std::string num(double v) {
    return CCsvWriter::num(v, 9);
}

void writePoseLine(std::ofstream& f, double t, const TPose2D& p) {
    char b[128];
    std::snprintf(b, sizeof(b), "%.3f %.6f %.6f %.6f\n", t, p.x, p.y, p.phi);
    f << b;
}
}  // namespace

// The run on the closed loop: a frame recorded each cycle, the route
// follower and the stopping rule commanding every sub-step.
struct CWorldSimulator::TRun : public CClosedLoop {
    TRun(CWorldSimulator& s, const CClosedLoop::TOptions& lo, COutputDir& out,
         size_t estFrames, bool quiet)
        : CClosedLoop(s.world, lo),
          sim(s),
          rawlog(out.stage("simulation.rawlog")),
          gtFile(out.stage("groundtruth.txt")),
          odoFile(out.stage("odometry.txt")),
          progress("simulate", estFrames, "frames", quiet) {}
    bool onCycle(int) override {
        sim.recordFrame(*this);
        return !done;
    }
    void onSubStep(int, int) override { sim.controlStep(*this); }
    CWorldSimulator& sim;
    CRawlogWriter rawlog;
    std::ofstream gtFile, odoFile;
    CProgress progress;
    std::vector<TPoint2D> gtTrack, odoTrack;
    mrpt::obs::CObservation2DRangeScan::Ptr lastScan;
    TPose2D start, lastOdo;
    double stoppedTime = 0;
    int stops = 0;
    bool blockedPrev = false, timeout = false, done = false;
};

void CWorldSimulator::recordFrame(TRun& r) {
    const double t = world.time();
    const TPose2D gt = world.truePose(), odo = world.odometricPose();
    const auto scans = world.sense();
    r.lastScan = scans.laser;
    mrpt::obs::CSensoryFrame sf;
    sf.insert(scans.laser);
    if (scans.range2)
        sf.insert(scans.range2);
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CActionRobotMovement2D mv;
    mv.timestamp = world.timestamp();
    // MRPT's default Gaussian motion model on the odometry increment.
    mv.computeFromOdometry(mrpt::poses::CPose2D(odo) - mrpt::poses::CPose2D(r.lastOdo),
                           mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    acts.insert(mv);
    r.rawlog.write(acts, sf);
    r.lastOdo = odo;
    writePoseLine(r.gtFile, simulation.start_time + t, gt);
    writePoseLine(r.odoFile, simulation.start_time + t, odo);
    r.gtTrack.emplace_back(gt.x, gt.y);
    r.odoTrack.emplace_back(odo.x, odo.y);
    r.progress.update(r.rawlog.frames());
    // (the loop ends at duration_max after this frame: status "timeout")
    if (route.finished() && std::abs(world.speed()) < 1e-9 &&
        std::abs(world.turnRate()) < 1e-9)
        r.done = true;
}

void CWorldSimulator::controlStep(TRun& r) {
    const double dt = simulation.sim_dt;
    double vDes = 0, wDes = 0;
    route.compute(world.truePose(), world.robot.max_w_deg * M_PI / 180.0,
                  world.robot.decel, vDes, wDes);
    world.command(vDes, wDes);
    common::TSpeedLimitInput in;
    in.robot = &world.robot;
    in.pose = world.truePose();
    in.desiredSpeed = std::max(0.0, world.commandedSpeed());
    in.scan = r.lastScan.get();
    const bool blocked = stopRule.limit(in).maxSpeed < in.desiredSpeed;
    if (blocked) {
        // Stop, but keep turning in place: a robot stopped askew in a doorway
        // would otherwise stay blocked by the door jamb forever.
        world.command(0, wDes);
        r.stoppedTime += dt;
        if (!r.blockedPrev)
            r.stops++;
    }
    r.blockedPrev = blocked;
}

json CWorldSimulator::run(COutputDir& out, bool quiet) {
    const auto wall0 = std::chrono::steady_clock::now();
    const double dt = simulation.sim_dt;
    const long stepsPerFrame = std::lround(1.0 / (simulation.frame_rate_hz * dt));

    route.reset();
    double estDuration = 0;
    for (size_t i = 1; i < route.points().size(); i++)
        estDuration += std::hypot(route.points()[i].x - route.points()[i - 1].x,
                                  route.points()[i].y - route.points()[i - 1].y) /
                       std::min(world.robot.max_v, route.legSpeeds()[i]);
    const size_t estFrames =
        size_t(std::min(simulation.duration_max, 1.1 * estDuration + 10) *
               simulation.frame_rate_hz);

    CClosedLoop::TOptions lo;
    lo.sim_dt = dt;
    lo.steps_per_cycle = int(stepsPerFrame);
    lo.duration_max = simulation.duration_max;
    lo.watch_corridor = true;
    lo.corridor_beta = simulation.relevance_beta;
    lo.corridor_lateral_margin = simulation.relevance_lateral_margin;
    lo.time_as_sum = true;
    TRun r(*this, lo, out, estFrames, quiet);
    r.start = route.startPose();
    world.reset(r.start, simulation.seed, simulation.start_time);
    r.lastOdo = world.odometricPose();
    r.safety.near_miss_distance = simulation.near_miss_distance;
    r.gtFile
        << "% t x y phi  (ground truth at each frame; t = UNIX time [s], phi [rad])\n";
    r.odoFile << "% t x y phi  (odometry at each frame, as logged in the rawlog)\n";

    r.timeout = r.run() == CClosedLoop::TEnd::Timeout;
    r.rawlog.close();
    for (auto [f, name] : {std::pair{&r.gtFile, "groundtruth.txt"},
                           std::pair{&r.odoFile, "odometry.txt"}}) {
        f->flush();
        const int err = errno;  // (the failed write's reason: a full disk)
        f->close();
        if (!*f)
            throw writeFailure(out.stage(name), err);
    }
    r.progress.finish();

    writeEventTables(r, out);
    saveGridmapGz(world.grid(), out.stage("map.gridmap.gz"));
    drawWorld(r, out.stage("world.png"));
    json j = summary(r, out);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const double duration = j["duration_s"].get<double>();
    j["timing"] = {{"wall_time_s", wall},
                   {"realtime_factor", wall > 0 ? duration / wall : 0.0}};
    return j;
}

void CWorldSimulator::writeEventTables(const TRun& r, COutputDir& out) const {
    {
        CCsvWriter csv(out.stage("agent_events.csv"),
                       {"t", "kind", "source", "agent", "x", "y"});
        // People's own events and their entries into the stopping corridor, by time.
        std::vector<TAgentEvent> all = world.agentEvents();
        const auto& entries = r.safety.corridorEntries();
        all.insert(all.end(), entries.begin(), entries.end());
        std::stable_sort(
            all.begin(), all.end(),
            [](const TAgentEvent& a, const TAgentEvent& b) { return a.t < b.t; });
        for (const auto& e : all)
            csv.row({CCsvWriter::fixed(simulation.start_time + e.t, 3), e.kind, e.source,
                     e.agent, num(e.x), num(e.y)});
        csv.close();
    }
    CCsvWriter csv(
        out.stage("safety_events.csv"),
        {"t", "kind", "object", "robot_x", "robot_y", "object_x", "object_y", "gap"});
    for (const auto& e : r.safety.events())
        csv.row({CCsvWriter::fixed(simulation.start_time + e.t, 3), e.kind, e.object,
                 num(e.rx), num(e.ry), num(e.ox), num(e.oy), num(e.gap)});
    csv.close();
}

namespace {
size_t countEvents(const std::vector<TAgentEvent>& events, const std::string& kind) {
    return size_t(std::count_if(events.begin(), events.end(),
                                [&](const TAgentEvent& e) { return e.kind == kind; }));
}
}  // namespace

void CWorldSimulator::drawWorld(const TRun& r, const std::string& path) const {
    const TPose2D start = r.start, endGt = world.truePose();
    const double duration = (r.rawlog.frames() - 1) / simulation.frame_rate_hz;
    const size_t emergences = countEvents(world.agentEvents(), "emerge");
    const int collisions = r.safety.collisions() + r.safety.collisionsStatic();
    CMapImage img(world.grid());
    img.polyline(route.waypoints(), {190, 190, 190}, 6);
    for (const auto& wk : world.agents.walkers)
        img.polyline(wk.path, {150, 110, 200}, 1, true);
    for (const auto& d : world.agents.doors) {
        img.polyline(d.path, {240, 190, 120}, 1, true);
        img.segment({d.door[0], d.door[1]}, {d.door[2], d.door[3]}, {230, 120, 0}, 5);
        img.text({d.door[2] + 0.1, d.door[3] + 0.1}, d.section, {160, 80, 0}, 0.4);
    }
    for (const auto& k : world.agents.clutter)
        img.circle({k.x, k.y}, k.radius, {140, 90, 40}, 1, true);
    img.polyline(r.odoTrack, {120, 120, 120}, 1, true);
    img.polyline(r.gtTrack, {0, 90, 200}, 2);
    for (const auto& e : world.agentEvents())
        if (e.kind == "emerge")
            img.marker({e.x, e.y}, CMapImage::TMarker::Triangle, {230, 120, 0}, 10, 2);
    for (const auto& e : r.safety.events())
        img.marker({e.ox, e.oy},
                   e.kind == "collision" ? CMapImage::TMarker::Cross
                                         : CMapImage::TMarker::Circle,
                   e.kind == "collision" ? TRgb{220, 0, 0} : TRgb{200, 0, 200}, 12, 2);
    img.marker({start.x, start.y}, CMapImage::TMarker::Square, {0, 160, 0}, 14, 2);
    img.marker({endGt.x, endGt.y}, CMapImage::TMarker::Star, {0, 0, 0}, 14, 2);
    img.legendLine("route", {190, 190, 190}, 6);
    img.legendLine("true path", {0, 90, 200}, 2);
    img.legendLine("odometry", {120, 120, 120}, 1);
    if (!world.agents.doors.empty())
        img.legendLine("door", {230, 120, 0}, 5);
    if (!world.agents.walkers.empty())
        img.legendLine("walker lane", {150, 110, 200}, 1);
    if (emergences)
        img.legendMarker("person emerged", CMapImage::TMarker::Triangle, {230, 120, 0});
    if (collisions)
        img.legendMarker("collision", CMapImage::TMarker::Cross, {220, 0, 0});
    if (r.safety.nearMisses())
        img.legendMarker("near miss", CMapImage::TMarker::Circle, {200, 0, 200});
    img.legendMarker("start", CMapImage::TMarker::Square, {0, 160, 0});
    img.legendMarker("end", CMapImage::TMarker::Star, {0, 0, 0});
    char title[256];
    std::snprintf(title, sizeof(title),
                  "risknav-simulate: %s  |  %.0f s, %.1f m, %zu frames, %d "
                  "collisions, %d near misses",
                  std::filesystem::path(world.mapSource.map_file).filename().c_str(),
                  duration, r.travelled(), r.rawlog.frames(), collisions,
                  r.safety.nearMisses());
    img.setTitle(title);
    img.save(path);
}

json CWorldSimulator::summary(const TRun& r, COutputDir& out) const {
    const auto& ev = world.agentEvents();
    const TPose2D endGt = world.truePose(), endOdo = world.odometricPose();
    const auto& g = world.grid();
    auto finiteOrNull = [](double x) {
        return std::isfinite(x) ? json(x) : json(nullptr);
    };
    json j;
    j["status"] = r.timeout ? "timeout" : "completed";
    j["frames"] = r.rawlog.frames();
    j["duration_s"] = (r.rawlog.frames() - 1) / simulation.frame_rate_hz;
    j["distance_m"] = r.travelled();
    j["route_length_m"] = route.length();
    j["laps"] = route.options.laps;
    j["collisions"] = r.safety.collisions() + r.safety.collisionsStatic();
    j["collisions_static"] = r.safety.collisionsStatic();
    j["near_misses"] = r.safety.nearMisses();
    j["min_clearance_agents_m"] = finiteOrNull(r.safety.minGapAgents());
    j["min_clearance_static_m"] = finiteOrNull(r.safety.minGapStatic());
    j["emergences"] = countEvents(ev, "emerge");
    j["relevant_emergences"] = r.safety.corridorEntries().size();
    j["walkers_spawned"] = countEvents(ev, "spawn");
    j["agents_gave_up"] = countEvents(ev, "give_up");
    j["stops"] = r.stops;
    j["stopped_time_s"] = r.stoppedTime;
    j["start_pose"] = {r.start.x, r.start.y, r.start.phi * 180 / M_PI};
    j["end_pose"] = {endGt.x, endGt.y, endGt.phi * 180 / M_PI};
    const auto& tg = world.odometry.trueGeometry();
    j["odometry"] = {
        {"error_model", world.odometry.options.error_model},
        {"final_position_error_m", std::hypot(endGt.x - endOdo.x, endGt.y - endOdo.y)},
        {"final_heading_error_deg",
         mrpt::math::wrapToPi(endOdo.phi - endGt.phi) * 180 / M_PI},
        {"true_wheel_geometry",
         {{"radius_l", tg.radiusL}, {"radius_r", tg.radiusR}, {"tread", tg.tread}}}};
    j["map"] = {{"file", world.mapSource.map_file},
                {"size_x", g.getSizeX()},
                {"size_y", g.getSizeY()},
                {"resolution", g.getResolution()},
                {"bounds", {g.getXMin(), g.getXMax(), g.getYMin(), g.getYMax()}}};
    json sensors = json::array();
    const auto& lo = world.laser.options;
    sensors.push_back({{"label", lo.label},
                       {"beams", lo.beams},
                       {"fov_deg", lo.fov_deg},
                       {"max_range", lo.max_range},
                       {"scans", r.rawlog.frames()}});
    const auto& ro = world.range2.options;
    if (ro.enabled)
        sensors.push_back({{"label", ro.label},
                           {"beams", ro.beams},
                           {"fov_deg", ro.fov_deg},
                           {"max_range", ro.max_range},
                           {"scans", world.range2Scans()}});
    j["sensors"] = sensors;
    j["outputs"] = out.stagedNames();
    return j;
}

void runSimulateApp(const TAppContext& ctx) {
    CWorldSimulator sim;
    sim.loadFromConfigFile(ctx.cfg, ctx.args.seed);
    COutputDir out(ctx.args.outDir, ctx.info.name);
    json summary = summaryHeader(ctx, sim.simulation.seed);
    summary.update(sim.run(out, ctx.args.quiet));
    mrpt::config::CConfigFileMemory effective;
    sim.saveToConfigFile(effective);
    out.writeText("config_effective.ini", effectiveConfigText(ctx.cfg.path(), effective));
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
