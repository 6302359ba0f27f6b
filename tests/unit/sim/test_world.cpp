#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/mapping/scan_points.h>
#include <risknav/sim/CRawlogWriter.h>
#include <risknav/sim/CSafetyMonitor.h>
#include <risknav/sim/CSimRobotInterface.h>
#include <risknav/sim/CSimWorld.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>
#include <risknav/sim/CWorldSimulator.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/CSimplePointsMap.h>

#include <gtest/gtest.h>
#include "sim_fixtures.h"
#include "test_support.h"

#include <cmath>
#include <set>
#include <sstream>

using namespace risknav::sim;
using mrpt::math::TPose2D;

namespace {
using risknav::test::emptyRoom;

void fastRobot(CSimWorld& w) {
    // Acceleration limits that reach any commanded speed within one step, so
    // that the motion is the ideal constant-twist arc from the start.
    w.robot.accel = w.robot.decel = 20;
    w.robot.w_accel_deg = 10000;
    w.odometry.options.error_model = "none";
}
}  // namespace

TEST(SimWorld, ConstantCommandDrivesTheArc) {
    CSimWorld w;
    fastRobot(w);
    w.setMap(emptyRoom());
    w.reset(TPose2D(0, 0, 0), 1);
    const double v = 0.5, om = 0.25, dt = 0.05;
    for (int i = 0; i < 80; i++)  // 4 s
        w.step(v, om, dt);
    const double T = 4.0, R = v / om;
    const TPose2D p = w.truePose();
    EXPECT_NEAR(w.time(), T, 1e-12);
    // On the circle of radius v / omega through the start, heading tangent.
    EXPECT_NEAR(p.x, R * std::sin(p.phi), 1e-3);
    EXPECT_NEAR(p.y, R * (1 - std::cos(p.phi)), 1e-3);
    // Exactly omega T: MRPT 2.5.8's simulateOneTimeStep(dt) ran its 0.5 ms
    // sub-steps past dt (4.0155 s of motion after 80 x 0.05 s); the world
    // steps its vehicle for dt exactly (CDiffDriveVehicle).
    EXPECT_NEAR(p.phi, om * T, 1e-9);
    EXPECT_NEAR(p.x, R * std::sin(om * T), 1e-9);
    // No odometry error: the odometry integrates the same twist.
    EXPECT_NEAR(w.odometricPose().phi, om * T, 1e-9);
    EXPECT_NEAR(w.odometricPose().x, R * std::sin(om * T), 1e-9);
    EXPECT_NEAR(w.speed(), v, 1e-12);
}

TEST(SimWorld, AccelerationLimitsAndSpeedClamp) {
    CSimWorld w;
    w.robot.accel = 0.5;
    w.robot.max_v = 0.8;
    w.setMap(emptyRoom());
    w.reset(TPose2D(0, 0, 0), 1);
    w.step(5.0, 0, 0.1);                  // asks far beyond max_v
    EXPECT_NEAR(w.speed(), 0.05, 1e-12);  // accel * dt
    for (int i = 0; i < 40; i++)
        w.step(5.0, 0, 0.1);
    EXPECT_NEAR(w.speed(), 0.8, 1e-12);  // clamped at max_v
}

TEST(SimWorld, PersonInFrontIsSensedAndIsAnMrptObstacle) {
    CSimWorld w;
    fastRobot(w);
    // A person walking across the robot's way 2 m ahead (spawns at t = 0).
    CAgentsSim::TWalker p;
    p.section = "CorridorWalker1";
    p.path = {{2.0, -1.0}, {2.0, 8.0}};
    p.speed_min = p.speed_max = 0.5;
    p.radius = 0.25;
    p.period = 1000;
    w.agents.walkers.push_back(p);
    w.setMap(emptyRoom());
    w.reset(TPose2D(0, 0, 0), 3);
    for (int i = 0; i < 40; i++)  // 2 s: the person is now at y ~ 0
        w.step(0, 0, 0.05);
    const auto discs = w.agents.discs();
    ASSERT_EQ(discs.size(), 1u);
    ASSERT_NEAR(discs[0].y, 0.0, 0.1);

    const auto scans = w.sense();
    ASSERT_TRUE(scans.laser);
    // The middle ray hits the person's front: 2 - 0.25 - the sensor's 0.2 m offset.
    const size_t mid = scans.laser->getScanSize() / 2;
    const double expected = 2.0 - 0.25 - w.laser.options.x;
    EXPECT_NEAR(scans.laser->getScanRange(mid), expected, 0.1);
    // The empty room's nearest wall ahead is 10 m away: nothing else is that close.
    size_t close = 0;
    for (const auto& q : risknav::mapping::scanToRobotFrame(*scans.laser))
        close += std::hypot(q.x - 2.0, q.y - discs[0].y) < 0.4;
    EXPECT_GT(close, 5u);

    CSimRobotInterface robot(w);
    mrpt::maps::CSimplePointsMap pts;
    mrpt::system::TTimeStamp ts;
    ASSERT_TRUE(robot.senseObstacles(pts, ts));
    size_t onPerson = 0;
    for (size_t i = 0; i < pts.size(); i++) {
        float x, y, z;
        pts.getPoint(i, x, y, z);
        onPerson += std::hypot(x - 2.0, y - discs[0].y) < 0.4;
    }
    EXPECT_GT(onPerson, 5u);

    // Without the person the same rays see the far wall.
    CSimWorld empty;
    fastRobot(empty);
    empty.setMap(emptyRoom());
    empty.reset(TPose2D(0, 0, 0), 3);
    const auto s2 = empty.sense();
    EXPECT_GT(s2.laser->getScanRange(mid), 7.5);  // beyond max_range 8 m or the wall
}

TEST(SimWorld, RobotInterfaceCommandsTheWorld) {
    CSimWorld w;
    fastRobot(w);
    w.setMap(emptyRoom());
    w.reset(TPose2D(1, 2, 0.5), 1);
    CSimRobotInterface robot(w);
    mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
    cmd.lin_vel = 0.3;
    cmd.ang_vel = 0.1;
    ASSERT_TRUE(robot.changeSpeeds(cmd));
    w.step(0.1);
    EXPECT_NEAR(w.speed(), 0.3, 1e-12);
    EXPECT_NEAR(w.turnRate(), 0.1, 1e-12);
    mrpt::math::TPose2D pose, odo;
    mrpt::math::TTwist2D vel;
    mrpt::system::TTimeStamp ts;
    std::string frame;
    ASSERT_TRUE(robot.getCurrentPoseAndSpeeds(pose, vel, ts, odo, frame));
    EXPECT_NEAR(pose.x, w.truePose().x, 1e-12);
    robot.setLocalization(TPose2D(5, 5, 0));
    ASSERT_TRUE(robot.getCurrentPoseAndSpeeds(pose, vel, ts, odo, frame));
    EXPECT_EQ(pose.x, 5.0);
    ASSERT_TRUE(robot.stop());
    w.step(0.1);
    EXPECT_EQ(w.speed(), 0.0);
}

TEST(Plugins, StoppingDistanceLimiterIsCreatedByName) {
    registerAllClasses_sim();
    auto byShort = risknav::common::CSpeedLimiter::Factory("CStoppingDistanceLimiter");
    ASSERT_TRUE(byShort);
    EXPECT_TRUE(std::dynamic_pointer_cast<CStoppingDistanceLimiter>(byShort));
    auto byFull =
        risknav::common::CSpeedLimiter::Factory("risknav::sim::CStoppingDistanceLimiter");
    EXPECT_TRUE(std::dynamic_pointer_cast<CStoppingDistanceLimiter>(byFull));
    // MRPT's own factory finds it too.
    EXPECT_TRUE(mrpt::rtti::classFactory("risknav::sim::CStoppingDistanceLimiter"));
    try {
        risknav::common::CSpeedLimiter::Factory("CNoSuchLimiter");
        FAIL() << "no error";
    } catch (const risknav::common::CBadInputError& e) {
        EXPECT_NE(std::string(e.what()).find("known: CStoppingDistanceLimiter"),
                  std::string::npos)
            << e.what();
    }
    // A registered MRPT class that is not a speed limiter is refused as well.
    EXPECT_THROW(risknav::common::CSpeedLimiter::Factory("CSimplePointsMap"),
                 risknav::common::CBadInputError);
}

TEST(Plugins, StoppingDistanceLimiterStopsForAPointAhead) {
    CStoppingDistanceLimiter lim;
    risknav::common::TRobotOptions robot;  // r 0.25, t_delay 0.9, decel 1
    mrpt::obs::CObservation2DRangeScan scan;
    scan.aperture = float(M_PI);
    scan.rightToLeft = true;
    scan.resizeScan(181);
    for (size_t i = 0; i < 181; i++) {
        scan.setScanRange(i, 5.0f);
        scan.setScanRangeValidity(i, true);
    }
    scan.setScanRange(90, 1.2f);  // straight ahead
    risknav::common::TSpeedLimitInput in;
    in.robot = &robot;
    in.scan = &scan;
    // 0.8 m/s: d_stop = 1.04 m > 1.2 - 0.25 front - 0.1 margin = 0.85 m free:
    // limited to the speed that stops within 0.85 m (d_stop(v) = 0.85).
    in.desiredSpeed = 0.8;
    const double v = lim.limit(in).maxSpeed;
    EXPECT_NEAR(risknav::common::stoppingDistance(v, 0.9, 1.0), 0.85, 1e-6);
    EXPECT_NEAR(v, std::sqrt(0.81 + 1.7) - 0.9, 1e-6);
    EXPECT_FALSE(lim.limit(in).reason.empty());
    // Along a path that turns left away from the point, nothing is in the way;
    // a path that runs into it stops at the first pose whose disc holds it.
    std::vector<mrpt::math::TPose2D> left, straight;
    std::vector<double> dist;
    for (int i = 0; i <= 60; i++) {
        const double s = 0.05 * i, R = 0.6;  // a 0.6 m radius left turn
        left.emplace_back(R * std::sin(s / R), R * (1 - std::cos(s / R)), s / R);
        straight.emplace_back(s, 0, 0);
        dist.push_back(s);
    }
    in.path = left;
    in.pathDistance = dist;
    lim.options.corridor = "path";
    EXPECT_EQ(lim.limit(in).maxSpeed, 0.8);
    lim.options.corridor = "both";  // the straight corridor still holds the point
    EXPECT_NEAR(lim.limit(in).maxSpeed, v, 1e-12);
    lim.options.corridor = "path";
    in.path = straight;
    // First disc (r 0.25 + lateral 0.1) holding x = 1.2: s = 0.85 m (to the
    // next 5 cm sample), less the 0.1 m margin.
    EXPECT_NEAR(risknav::common::stoppingDistance(lim.limit(in).maxSpeed, 0.9, 1.0),
                0.775, 0.026);
    in.path.clear();
    in.pathDistance.clear();
    lim.options.corridor = "both";
    // 0.5 m/s: d_stop = 0.575 m + 0.1 < 0.95: drive on.
    in.desiredSpeed = 0.5;
    EXPECT_EQ(lim.limit(in).maxSpeed, 0.5);
    in.desiredSpeed = -1;
    EXPECT_THROW(lim.limit(in), std::invalid_argument);
}

TEST(SafetyMonitor, DoorPedestrianEnteringTheStoppingCorridorIsLoggedOnce) {
    CAgentsSim agents;
    CAgentsSim::TDoorPedestrian d;
    d.section = "DoorPedestrian1";
    d.door[0] = 1.5;
    d.door[1] = 1.0;
    d.door[2] = 2.5;
    d.door[3] = 1.0;
    d.path = {{2.0, 1.0}, {2.0, -1.0}};  // crosses the robot's line 2 m ahead
    d.emergence = "schedule";
    d.schedule = {0.0};
    d.speed = 0.5;
    agents.doors.push_back(d);
    agents.reset(1);
    std::vector<TAgentEvent> ev;
    agents.step(0.05, 0.05, TPose2D(0, 0, 0), 0.25, ev);
    ASSERT_EQ(agents.discs().size(), 1u);
    CSafetyMonitor m;
    // Robot at the origin heading +x, reach 1.0 m beyond its front (1.25 m).
    const double reach = 1.0, halfW = 0.35;
    m.updateCorridor(0.1, TPose2D(0, 0, 0), 0.5, 0.25, reach, halfW, agents);
    EXPECT_TRUE(m.corridorEntries().empty());  // at y = 1: beside, not in, the corridor
    for (int i = 0; i < 30; i++)
        agents.step(0.1 + 0.05 * i, 0.05, TPose2D(0, 0, 0), 0.25, ev);
    m.updateCorridor(1.6, TPose2D(0, 0, 0), 0.0, 0.25, reach, halfW, agents);
    EXPECT_TRUE(m.corridorEntries().empty());  // the robot stands: not relevant
    m.updateCorridor(1.6, TPose2D(0, 0, M_PI), 0.5, 0.25, reach, halfW, agents);
    EXPECT_TRUE(m.corridorEntries().empty());  // behind the robot
    m.updateCorridor(1.7, TPose2D(0.9, 0, 0), 0.5, 0.25, reach, halfW, agents);
    ASSERT_EQ(m.corridorEntries().size(), 1u);  // 1.1 m ahead, on the line
    EXPECT_EQ(m.corridorEntries()[0].source, "DoorPedestrian1");
    m.updateCorridor(1.8, TPose2D(0.9, 0, 0), 0.5, 0.25, reach, halfW, agents);
    EXPECT_EQ(m.corridorEntries().size(), 1u);  // once per person
}

TEST(CRawlogWriter, AFullDiskNamesTheFile) {
    // /dev/full fails every write with ENOSPC: the error names the file.
    std::string err;
    try {
        CRawlogWriter w("/dev/full", 0);
        mrpt::obs::CActionCollection acts;
        mrpt::obs::CSensoryFrame sf;
        auto scan = mrpt::obs::CObservation2DRangeScan::Create();
        scan->resizeScan(2000);
        sf.insert(scan);
        for (int i = 0; i < 200; i++)  // beyond any buffer
            w.write(acts, sf);
        w.close();
    } catch (const std::runtime_error& e) {
        err = e.what();
    }
    EXPECT_NE(err.find("/dev/full"), std::string::npos) << err;
}

// The one start check of every app, in metres (the distance field's whole
// cells let a start 0.20 m from a wall pass for a 0.25 m robot).
TEST(SimWorld, PlacementIsCheckedInMetres) {
    mrpt::maps::COccupancyGridMap2D g(-10, 10, -10, 10, 0.05f);
    g.fill(1.0f);
    for (int iy = 0; iy < int(g.getSizeY()); iy++)
        for (int ix = g.x2idx(1.0 + 0.025); ix < int(g.getSizeX()); ix++)
            g.setCell(ix, iy, 0.0f);  // a wall from x = 1.0 m on
    CSimWorld w;
    w.robot.radius = 0.25;
    CAgentsSim::TClutter k;
    k.section = "Clutter1";
    k.x = -5;
    k.y = 0;
    k.radius = 0.3;
    w.agents.clutter.push_back(k);
    w.setMap(g);
    EXPECT_NEAR(w.pointClearance(0.80, 0), 0.20, 1e-6);
    const auto near = w.placement(0.80, 0);
    EXPECT_FALSE(near.free());
    EXPECT_EQ(near.with, "the map");
    EXPECT_EQ(near.why, "is inside an obstacle (clearance 0.20 m < robot radius 0.25 m)");
    EXPECT_TRUE(w.placement(0.74, 0).free());   // 0.26 m
    EXPECT_FALSE(w.placement(0.76, 0).free());  // 0.24 m
    const auto off = w.placement(0, 12);
    EXPECT_EQ(off.why, "is outside the map");
    const auto onDisc = w.placement(-5.5, 0);  // 0.5 m < 0.3 + 0.25
    EXPECT_EQ(onDisc.with, "[Clutter1]");
    EXPECT_EQ(onDisc.why,
              "is inside [Clutter1] (0.50 m from its centre < 0.30 m + robot radius "
              "0.25 m)");
    EXPECT_TRUE(w.placement(-5.6, 0).free());
}

namespace {
// A free 10 x 6 m map, [-2, 8] x [-3, 3], with a block of unknown cells
// (grey, P(free) = 0.5: never seen) over x in [3, 4], y in [-1, 1].
mrpt::maps::COccupancyGridMap2D mapWithUnknownBlock() {
    mrpt::maps::COccupancyGridMap2D g(-2, 8, -3, 3, 0.05f);
    g.fill(1.0f);
    for (int cy = g.y2idx(-1.0 + 0.025); cy <= g.y2idx(1.0 - 0.025); cy++)
        for (int cx = g.x2idx(3.0 + 0.025); cx <= g.x2idx(4.0 - 0.025); cx++)
            g.setCell(cx, cy, 0.5f);
    return g;
}

struct TDriveIntoBlock {
    bool echo = false;
    double range = 0;  ///< the middle beam's, when it echoes [m]
    int collisions = 0;
    double minGap = 0;
};

// The robot at (0, 0) facing the block senses once, then drives 5.5 m
// straight on (through the block when it may), as the simulator counts
// collisions (CWorldSimulator: pointClearance into CSafetyMonitor).
TDriveIntoBlock driveIntoBlock(bool unknownIsObstacle) {
    CSimWorld w;
    fastRobot(w);
    w.obstacleRule.unknown_is_obstacle = unknownIsObstacle;
    w.laser.options.max_range = 5.0;  // the map's far edge (8 m) out of range
    w.laser.options.noise_std = 0;
    w.setMap(mapWithUnknownBlock());
    w.reset(TPose2D(0, 0, 0), 1);
    TDriveIntoBlock r;
    const auto scan = w.sense().laser;
    const size_t mid = scan->getScanSize() / 2;
    r.echo = scan->getScanRangeValidity(mid);
    r.range = scan->getScanRange(mid);
    CSafetyMonitor m;
    const double dt = 0.05;
    for (int i = 0; i < 220; i++) {  // 0.5 m/s for 11 s
        w.step(0.5, 0, dt);
        const auto p = w.truePose();
        m.update(w.time(), p, w.robot.radius, w.agents, w.pointClearance(p.x, p.y));
    }
    r.collisions = m.collisionsStatic();
    r.minGap = m.minGapStatic();
    return r;
}
}  // namespace

// [World] unknown_is_obstacle = true (the default): the unknown block is a
// wall for the laser (an echo at its edge) and for the collisions.
TEST(SimWorld, UnknownCellsAreWallsForTheLaserAndTheCollisions) {
    EXPECT_TRUE(CSimWorld().obstacleRule.unknown_is_obstacle);  // the default
    const auto r = driveIntoBlock(true);
    ASSERT_TRUE(r.echo);
    EXPECT_NEAR(r.range, 3.0 - 0.2, 0.05);  // the block's edge, from the sensor
    EXPECT_EQ(r.collisions, 1);
    EXPECT_LT(r.minGap, 0);
}

// unknown_is_obstacle = false: the block is free for both, no echo (nothing
// else within the laser's 5 m) and no collision driving through it.
TEST(SimWorld, UnknownCellsAreFreeForTheLaserAndTheCollisionsWhenNotObstacles) {
    const auto r = driveIntoBlock(false);
    EXPECT_FALSE(r.echo);
    EXPECT_EQ(r.collisions, 0);
    EXPECT_GT(r.minGap, 1.5);  // the map's edge 2 m behind the start is the nearest
}

// Whatever the rule, the world's laser and its collision check classify
// every cell alike (CRayCastMap and CDistanceField through one function).
TEST(SimWorld, LaserAndCollisionsSeeTheSameCells) {
    for (const bool unknown : {true, false}) {
        CSimWorld w;
        w.obstacleRule.unknown_is_obstacle = unknown;
        w.setMap(mapWithUnknownBlock());
        const auto& f = w.distanceField();
        for (int cy = -1; cy <= f.sizeY(); cy++)
            for (int cx = -1; cx <= f.sizeX(); cx++)
                ASSERT_EQ(w.rayCastMap().isObstacleAt(f.idx2x(cx), f.idx2y(cy)),
                          f.isObstacle(cx, cy))
                    << cx << ", " << cy;
    }
}

// config/risknav-simulate.ini documents every key the declared options read,
// under its section, with the value the app runs with by default (where it
// does not set another on purpose): the declarations are the one place the
// keys are named.
namespace {
void expectDocumented(const mrpt::config::CConfigFileBase& doc,
                      const std::string& section,
                      const risknav::common::CDeclaredOptions& o,
                      const std::set<std::string>& notDefault = {},
                      const std::set<std::string>& commentedOut = {}) {
    const auto keys = o.keys();
    ASSERT_FALSE(keys.empty());
    for (const auto& k : keys) {
        EXPECT_FALSE(k.doc.empty()) << "[" << section << "] " << k.key;
        if (commentedOut.count(k.key))
            continue;  // an optional key, documented but not set
        EXPECT_TRUE(doc.keyExists(section, k.key)) << "[" << section << "] " << k.key;
        if (notDefault.count(k.key))
            continue;
        // the value before its comment, as the declaration writes it ("1.0": "1")
        std::string v = doc.read_string(section, k.key, "");
        v = v.substr(0, v.find_first_of(" \t/"));
        double x = 0;
        if (risknav::common::parseNumber(v, x))
            v = risknav::common::numberText(x);
        EXPECT_EQ(v, k.defaultText) << "[" << section << "] " << k.key;
    }
}

std::string simulateText() {
    return risknav::test::readFile(
        risknav::test::sourcePath("config/risknav-simulate.ini"));
}

mrpt::config::CConfigFileMemory simulateIni() {
    return mrpt::config::CConfigFileMemory(simulateText());
}

// The keys a section documents commented out ("; key = value"): optional
// keys, which the example leaves unset.
std::set<std::string> commentedKeys(const std::string& section) {
    std::set<std::string> keys;
    std::istringstream in(simulateText());
    bool inside = false;
    for (std::string l; std::getline(in, l);) {
        if (!l.empty() && l[0] == '[') {
            inside = l.rfind("[" + section + "]", 0) == 0;
            continue;
        }
        const auto eq = l.find('=');
        if (!inside || l.empty() || l[0] != ';' || eq == std::string::npos)
            continue;
        std::istringstream k(l.substr(1, eq - 1));
        std::string key, more;
        if (k >> key && !(k >> more))
            keys.insert(key);
    }
    return keys;
}
}  // namespace

TEST(DeclaredOptions, TheSimulateConfigDocumentsEveryDeclaredKey) {
    const auto doc = simulateIni();
    // duration_max: the example world runs 600 s of the 3600 s default
    expectDocumented(doc, "Simulation", CWorldSimulator::TSimulationOptions(),
                     {"duration_max"});
    const CSimWorld w;
    expectDocumented(doc, "World", w.mapSource, {"map_file"});
    expectDocumented(doc, "World", w.obstacleRule);
    expectDocumented(doc, "Robot", w.robot);
    expectDocumented(doc, "Odometry", w.odometry.options);
    expectDocumented(doc, "Laser", w.laser.options);
    // the second sensor's defaults are the world's, not the struct's; the
    // example scans every 2nd frame
    expectDocumented(doc, "RangeSensor2", w.range2.options, {"frame_decimation"});
    expectDocumented(doc, "CStoppingDistanceLimiter",
                     CStoppingDistanceLimiter::TOptions());
}

TEST(DeclaredOptions, TheSimulateConfigDocumentsTheRouteAndTheAgents) {
    const auto doc = simulateIni();
    // speeds and start_heading_deg are optional: documented commented out
    const std::set<std::string> optional = {"speeds", "start_heading_deg"};
    for (const auto& k : optional)
        EXPECT_EQ(commentedKeys("Route").count(k), 1u) << "[Route] " << k;
    expectDocumented(doc, "Route", CRouteFollower::TOptions(), {"waypoints"}, optional);
    // the example's door, path and people differ from the defaults on purpose
    expectDocumented(
        doc, "DoorPedestrian1", CAgentsSim::TDoorPedestrian(),
        {"door", "path", "schedule", "trigger_distance", "trigger_probability"});
    expectDocumented(doc, "CorridorWalker1", CAgentsSim::TWalker(),
                     {"path", "period", "phase"});
    expectDocumented(doc, "Clutter1", CAgentsSim::TClutter(), {"x", "y", "radius"});
}

TEST(DeclaredOptions, TheRouteAndTheAgentsSaveWhatTheyLoad) {
    // config_effective.ini's [Route] and agent sections: the same values,
    // each with its doc and range, loading back to the same structs
    const auto doc = simulateIni();
    CRouteFollower::TOptions route;
    CAgentsSim agents;
    route.loadFromConfigFile(doc, "Route");
    agents.loadFromConfigFile(doc);
    ASSERT_EQ(agents.doors.size(), 1u);
    ASSERT_EQ(agents.walkers.size(), 1u);
    ASSERT_EQ(agents.clutter.size(), 1u);
    EXPECT_EQ(agents.doors[0].door[2], 12.02);
    EXPECT_EQ(agents.doors[0].path.size(), 3u);
    EXPECT_EQ(agents.doors[0].schedule, (std::vector<double>{30, 90}));
    EXPECT_FALSE(route.start_heading_deg);
    mrpt::config::CConfigFileMemory saved;
    route.saveToConfigFile(saved, "Route");
    agents.saveToConfigFile(saved);
    const std::string text = saved.getContent();
    EXPECT_NE(text.find("waypoints = 2 4.5 28 4.5 // x0 y0 x1 y1"), std::string::npos)
        << text;
    EXPECT_NE(text.find("door = 11.21 6.07 12.02 6.07 // "), std::string::npos) << text;
    EXPECT_NE(text.find("x = 8.3 // "), std::string::npos) << text;
    // optional keys left unset are not written
    EXPECT_EQ(text.find("speeds"), std::string::npos) << text;
    EXPECT_EQ(text.find("start_heading_deg"), std::string::npos) << text;
    const mrpt::config::CConfigFileMemory back(text);
    CRouteFollower::TOptions route2;
    CAgentsSim agents2;
    route2.loadFromConfigFile(back, "Route");
    agents2.loadFromConfigFile(back);
    auto same = [](const risknav::common::CDeclaredOptions& a,
                   const risknav::common::CDeclaredOptions& b) {
        const auto ka = a.keys(), kb = b.keys();
        ASSERT_EQ(ka.size(), kb.size());
        for (size_t i = 0; i < ka.size(); i++)
            EXPECT_EQ(ka[i].defaultText, kb[i].defaultText) << ka[i].key;
    };
    same(route, route2);
    ASSERT_EQ(agents2.doors.size(), 1u);
    ASSERT_EQ(agents2.walkers.size(), 1u);
    ASSERT_EQ(agents2.clutter.size(), 1u);
    same(agents.doors[0], agents2.doors[0]);
    same(agents.walkers[0], agents2.walkers[0]);
    same(agents.clutter[0], agents2.clutter[0]);
    EXPECT_EQ(agents2.clutter[0].section, "Clutter1");
}

TEST(DeclaredOptions, TheAgentsRequiredKeysAndRulesNameTheirSection) {
    auto errorOf = [](const std::string& ini) {
        try {
            CAgentsSim a;
            a.loadFromConfigFile(mrpt::config::CConfigFileMemory(ini));
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    auto has = [](const std::string& err, const std::string& part) {
        EXPECT_NE(err.find(part), std::string::npos) << err;
    };
    has(errorOf("[Clutter3]\nx = 1\n"), "[Clutter3] y: required key is missing");
    has(errorOf("[DoorPedestrian2]\ndoor = 0 0 1\npath = 0 0 1 1\n"),
        "[DoorPedestrian2] door = '0 0 1': needs exactly 4 numbers");
    has(errorOf("[DoorPedestrian2]\ndoor = 0 0 1 0\n"),
        "[DoorPedestrian2] path: required key is missing");
    has(errorOf("[CorridorWalker2]\npath = 0 0\n"),
        "[CorridorWalker2] path = '0 0': needs at least 4 numbers");
    has(errorOf("[CorridorWalker2]\npath = 0 0 0 0\n"),
        "[CorridorWalker2] path = '0 0 0 0': has two equal consecutive points");
    has(errorOf("[DoorPedestrian2]\ndoor = 0 0 1 0\npath = 0 0 1 1\nemergence = "
                "schedule\n"),
        "[DoorPedestrian2] schedule = '': required when emergence = schedule");
    has(errorOf("[DoorPedestrian2]\ndoor = 0 0 1 0\npath = 0 0 1 1\nschedule = 5 2\n"),
        "[DoorPedestrian2] schedule = '5 2': times must be increasing");
    has(errorOf("[CorridorWalker2]\npath = 0 0 1 1\nspeed_min = 1.9\nspeed_max = 1.7\n"),
        "[CorridorWalker2] speed_max = '1.7': must be >= speed_min");
    CRouteFollower::TOptions r;
    r.waypoints = {0, 0, 1, 0, 2, 0};
    r.speeds = {0.3};
    try {
        r.validate();
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "[Route] speeds = '0.3': needs one speed per segment (2)");
    }
}

TEST(DeclaredOptions, TheSavedKeysCarryTheirDocAndRangeAndLoadBack) {
    // the documented values, saved as config_effective.ini saves them and
    // read back: the same values, each with its doc and range as comment
    const auto doc = simulateIni();
    CWorldSimulator::TSimulationOptions sim;
    CSimWorld w;
    CStoppingDistanceLimiter::TOptions stop;
    sim.loadFromConfigFile(doc, "Simulation");
    w.robot.loadFromConfigFile(doc, "Robot");
    w.odometry.options.loadFromConfigFile(doc, "Odometry");
    w.obstacleRule.loadFromConfigFile(doc, "World");
    w.range2.options.loadFromConfigFile(doc, "RangeSensor2");
    stop.loadFromConfigFile(doc, "CStoppingDistanceLimiter");
    mrpt::config::CConfigFileMemory saved;
    sim.saveToConfigFile(saved, "Simulation");
    w.robot.saveToConfigFile(saved, "Robot");
    w.odometry.options.saveToConfigFile(saved, "Odometry");
    w.obstacleRule.saveToConfigFile(saved, "World");
    w.range2.options.saveToConfigFile(saved, "RangeSensor2");
    stop.saveToConfigFile(saved, "CStoppingDistanceLimiter");
    const std::string text = saved.getContent();
    EXPECT_NE(text.find("// the robot is a disc, (0, 5] m"), std::string::npos) << text;
    EXPECT_NE(text.find("// errors drawn once per run, every step, or none, systematic | "
                        "per_step | none"),
              std::string::npos)
        << text;
    const mrpt::config::CConfigFileMemory back(text);
    CWorldSimulator::TSimulationOptions sim2;
    CSimWorld w2;
    CStoppingDistanceLimiter::TOptions stop2;
    sim2.loadFromConfigFile(back, "Simulation");
    w2.robot.loadFromConfigFile(back, "Robot");
    w2.odometry.options.loadFromConfigFile(back, "Odometry");
    w2.obstacleRule.loadFromConfigFile(back, "World");
    w2.range2.options.loadFromConfigFile(back, "RangeSensor2");
    stop2.loadFromConfigFile(back, "CStoppingDistanceLimiter");
    auto same = [](const risknav::common::CDeclaredOptions& a,
                   const risknav::common::CDeclaredOptions& b) {
        const auto ka = a.keys(), kb = b.keys();
        ASSERT_EQ(ka.size(), kb.size());
        for (size_t i = 0; i < ka.size(); i++)
            EXPECT_EQ(ka[i].defaultText, kb[i].defaultText) << ka[i].key;
    };
    same(sim, sim2);
    same(w.robot, w2.robot);
    same(w.odometry.options, w2.odometry.options);
    same(w.obstacleRule, w2.obstacleRule);
    same(w.range2.options, w2.range2.options);
    same(stop, stop2);
    EXPECT_EQ(sim2.duration_max, 600);
    EXPECT_EQ(w2.range2.options.label, "RANGE2");
}

TEST(DeclaredOptions, RangeErrorsNameTheSectionRead) {
    CSimWorld w;
    w.robot.max_v = 0;
    try {
        w.robot.validate();
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "[Robot] max_v = '0': must be in (0, 5] m/s");
    }
    w.range2.options.beams = 1;
    try {
        w.range2.options.validate();
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "[RangeSensor2] beams = '1': must be in [2, 10000]");
    }
}
