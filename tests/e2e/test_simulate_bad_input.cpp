// Bad input to risknav-simulate: exit code 2, exactly one line on stderr that
// names the problem, and an existing output folder left exactly as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "test_support.h"

using namespace risknav::test;
namespace fs = std::filesystem;

namespace {
struct TCase {
    std::string name;
    std::string edit_from,
        edit_to;  // regex replacement applied to the corridor world.ini
    std::string extraArgs;
    std::string expect;  // substring of the one-line error
};

std::ostream& operator<<(std::ostream& o, const TCase& c) {
    return o << c.name;
}

class BadInput : public ::testing::TestWithParam<TCase> {};
}  // namespace

TEST_P(BadInput, ExitTwoOneLineOutputUntouched) {
    const TCase& c = GetParam();
    const std::string work = freshDir("world");
    fs::copy_file(sourcePath("datasets/corridor-doors/corridor.png"),
                  work + "/corridor.png");
    writeFile(work + "/not_a_png.png", "plain text, not an image\n");
    // A real PNG cut short: libpng's own complaint must not reach stderr.
    const std::string png = readFile(sourcePath("datasets/corridor-doors/corridor.png"));
    writeFile(work + "/truncated.png", png.substr(0, png.size() / 3));
    std::string ini = readFile(sourcePath("datasets/corridor-doors/world.ini"));
    if (!c.edit_from.empty()) {
        const std::string edited =
            std::regex_replace(ini, std::regex(c.edit_from), c.edit_to);
        ASSERT_NE(edited, ini) << "the edit did not apply";
        ini = edited;
    }
    writeFile(work + "/world.ini", ini);

    // An earlier run's results in the output folder.
    const std::string out = freshDir("out");
    const TEarlierOutput earlier = {{"simulation.rawlog", "earlier rawlog"},
                                    {"summary.json", "{\"earlier\": true}\n"}};
    writeEarlierOutput(out, earlier);
    const std::string cfg =
        c.name == "missing_config" ? work + "/nope.ini" : work + "/world.ini";

    const auto r = run(binPath("risknav-simulate") + " -q -o '" + out + "' " +
                       c.extraArgs + " '" + cfg + "'");
    expectBadInput(r, c.expect, out, earlier, "risknav-simulate: error: ");
}

INSTANTIATE_TEST_SUITE_P(
    Simulate, BadInput,
    ::testing::Values(
        TCase{"missing_config", "", "", "", "nope.ini: config file not found"},
        TCase{"truncated_png", "map_file       = corridor.png",
              "map_file       = truncated.png", "",
              "truncated.png: cannot read the map image"},
        TCase{"duplicated_key", "\\[Robot\\]\n", "[Robot]\nradius = 0.3\n", "",
              "[Robot] radius is given twice"},
        TCase{"line_without_equals", "\\[Robot\\]\n", "[Robot]\nmax_v    1.1\n", "",
              "'max_v    1.1' in [Robot]: expected KEY = VALUE"},
        TCase{"missing_map", "map_file\\s*=\\s*corridor.png", "map_file = nothere.png",
              "", "[World] map_file = 'nothere.png': file not found"},
        TCase{"unreadable_png", "map_file\\s*=\\s*corridor.png",
              "map_file = not_a_png.png", "", "not_a_png.png: cannot read the map image"},
        TCase{"missing_waypoints", "waypoints = [^\n]*\n", "", "",
              "[Route] waypoints: required key is missing"},
        TCase{"negative_speed", "speed\\s*=\\s*0.2", "speed = -0.2", "",
              "[Route] speed = '-0.2': must be in (0, 5] m/s"},
        TCase{"zero_resolution", "", "", "--set World.map_resolution=0",
              "[World] map_resolution = '0': must be in [0.001, 10] m"},
        // the obstacle rule's switches are booleans (laser and collisions
        // both follow them: a misread one would change what is a wall)
        TCase{"unknown_is_obstacle_not_a_bool", "\\[World\\]\n",
              "[World]\nunknown_is_obstacle = maybe\n", "",
              "world.ini: [World] unknown_is_obstacle = 'maybe': must be true or false"},
        TCase{"negative_person_speed", "speed     = 0.8", "speed     = -0.8", "",
              "[DoorPedestrian1] speed = '-0.8': must be in (0, 10] m/s"},
        TCase{"not_a_number", "", "", "--set Robot.radius=0.25cm",
              "[Robot] radius = '0.25cm': not a number"},
        TCase{"unknown_key", "\\[Robot\\]\n", "[Robot]\nmax_vel = 1.0\n", "",
              "unknown key [Robot] max_vel"},
        TCase{"unknown_key_by_set", "", "", "--set Route.sped=1",
              "unknown key [Route] sped"},
        TCase{"unknown_section", "\\[Robot\\]", "[Robto]", "", "unknown section [Robto]"},
        TCase{"route_through_wall", "waypoints = 2.0 4.5  28.0 4.5",
              "waypoints = 2.0 4.5  2.0 8.0", "", "runs through an obstacle"},
        TCase{"start_in_obstacle", "waypoints = 2.0 4.5  28.0 4.5",
              "waypoints = 2.0 1.0  28.0 4.5", "",
              "start (2.00, 1.00) is inside an obstacle"},
        // in metres, as risknav-navigate and -explore check it (the
        // distance field's whole cells let it run and collide at t = 0)
        TCase{"start_0_20_m_from_wall", "waypoints = 2.0 4.5  28.0 4.5",
              "waypoints = 2.0 3.2  2.0 4.5  28.0 4.5", "",
              "start (2.00, 3.20) is inside an obstacle (clearance 0.20 m < robot "
              "radius 0.25 m)"},
        TCase{"start_on_clutter", "\\[Robot\\]\n",
              "[Clutter9]\nx = 2.0\ny = 4.5\n\n[Robot]\n", "",
              "start (2.00, 4.50) is inside [Clutter9]"},
        TCase{"waypoint_off_map", "waypoints = 2.0 4.5  28.0 4.5",
              "waypoints = 2.0 4.5  35.0 4.5", "", "is outside the map"},
        TCase{"odd_waypoints", "waypoints = 2.0 4.5  28.0 4.5",
              "waypoints = 2.0 4.5  28.0 4.5 3.0", "", "needs a multiple of 2 numbers"},
        TCase{"huge_sigma", "sigma_tread        = 0.001", "sigma_tread        = 0.5", "",
              "[Odometry] sigma_tread = '0.5': must be < tread / 3"},
        TCase{"bad_choice", "error_model        = systematic",
              "error_model        = random", "",
              "must be one of: systematic, per_step, none"},
        TCase{"frame_not_multiple_of_dt", "", "", "--set Simulation.sim_dt=0.07",
              "whole multiple of sim_dt"},
        TCase{"laser_decimation", "", "", "--set Laser.frame_decimation=2",
              "[Laser] frame_decimation must be 1"},
        // the run's work bounded before it starts (unbounded, a run wrote 1.6 GB in
        // 3 minutes on its way to 1e6 s with the robot stopped by clutter)
        TCase{"run_too_long", "", "",
              "--set Simulation.sim_dt=0.01 --set Simulation.duration_max=1e6",
              "[Simulation] duration_max = '1e6': is 1e+08 steps of sim_dt = 0.01 s, at "
              "most 2e+07"},
        TCase{"output_too_big", "", "",
              "--set Simulation.duration_max=1e6 --set Laser.beams=1081",
              "frames of 1081 ranges, at most 5e+08 ranges in all"},
        // people and clutter where the map has walls, a route of no
        // length, a person at 1e308 m/s
        TCase{"walker_in_a_wall", "", "", "--set 'CorridorWalker1.path=0.7 0.1 29.3 0.1'",
              "[CorridorWalker1] path = '0.7 0.1 29.3 0.1': segment 1 runs through an "
              "obstacle of the map at (0.70, 0.10)"},
        TCase{"pedestrian_through_walls", "", "",
              "--set 'DoorPedestrian1.path=11.6 9.9 11.6 0.1'",
              "[DoorPedestrian1] path = '11.6 9.9 11.6 0.1': segment 1 runs through an "
              "obstacle"},
        TCase{"door_off_map", "", "", "--set 'DoorPedestrian1.door=100 100 101 100'",
              "[DoorPedestrian1] door = '100 100 101 100': point (100.00, 100.00) is "
              "outside the map"},
        TCase{"clutter_in_a_wall", "", "", "--set Clutter1.x=0 --set Clutter1.y=4.5",
              "[Clutter1] x, y: (0.00, 4.50) lies inside an obstacle of the map"},
        TCase{"route_of_no_length", "", "", "--set 'Route.waypoints=2 4.5 2 4.5'",
              "[Route] waypoints = '2 4.5 2 4.5': the route has no length"},
        TCase{"person_speed_huge", "", "", "--set DoorPedestrian1.speed=1e308",
              "[DoorPedestrian1] speed = '1e308': must be in (0, 10] m/s"},
        TCase{"walker_speed_huge", "", "", "--set CorridorWalker1.speed_max=1e308",
              "[CorridorWalker1] speed_max = '1e308': must be in (0, 10] m/s"},
        TCase{"bad_option", "", "", "--frobnicate", "unknown option '--frobnicate'"},
        // (-o is given by the harness too: the second one is refused first)
        TCase{"out_given_twice", "", "", "--out \"$(printf 'a\\nb')\"",
              "--out: the output directory is given twice"},
        TCase{"bad_seed", "", "", "--seed -1",
              "--seed '-1': must be an integer in [0, 9007199254740992]"},
        // beyond 2^53 the config's seed key refuses it: config_effective.ini
        // would not load back
        TCase{"seed_beyond_2_53", "", "", "--seed 9007199254740993",
              "--seed '9007199254740993': must be an integer in [0, 9007199254740992]"}),
    [](const ::testing::TestParamInfo<TCase>& i) { return i.param.name; });
