// risknav-simulate drives the commanded speed at every physics step it
// accepts: MRPT's vehicle simulator stepped past dt (0.24 m/s for 0.2 at
// sim_dt = 0.001; a corridor lap 190 s instead of 261 s).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "test_support.h"

using namespace risknav::test;

namespace {
struct TGt {
    double t, x, y, phi;
};

std::vector<TGt> readGt(const std::string& f) {
    std::vector<TGt> v;
    for (const auto& l : readLines(f)) {
        if (l.empty() || l[0] == '%')
            continue;
        std::istringstream s(l);
        TGt p{};
        s >> p.t >> p.x >> p.y >> p.phi;
        v.push_back(p);
    }
    return v;
}
}  // namespace

TEST(SimulatePhysics, StraightLegAtCommandedSpeedForEverySimDt) {
    for (const double dt : {0.001, 0.005, 0.01, 0.05, 0.1}) {
        const std::string work = freshDir("physics");
        // The corridor's centre line once at 0.2 m/s: no people, no odometry
        // errors, nothing to stop for.
        writeFile(work + "/world.ini",
                  "[Simulation]\nsim_dt = " + std::to_string(dt) +
                      "\nframe_rate_hz = 5\nduration_max = 400\nseed = 1\n"
                      "start_time = 0\n[World]\nmap_file = " +
                      sourcePath("datasets/corridor-doors/corridor.png") +
                      "\n[Robot]\nradius = 0.25\nmax_v = 0.8\naccel = 1\ndecel = 1\n"
                      "[Odometry]\nerror_model = none\n"
                      "[Route]\nwaypoints = 2.0 4.5  28.0 4.5\nspeed = 0.2\nmode = once\n"
                      "laps = 1\n");
        const std::string out = freshDir("physics-out");
        const auto r = run(binPath("risknav-simulate") + " -q -o '" + out + "' '" + work +
                           "/world.ini'");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const auto gt = readGt(out + "/groundtruth.txt");
        const TGt *a = nullptr, *b = nullptr;
        for (const auto& p : gt) {
            if (!a && p.x >= 5.0)
                a = &p;
            if (p.x <= 25.0)
                b = &p;
        }
        ASSERT_TRUE(a && b && b->t - a->t > 90) << "sim_dt " << dt;
        // 20 m at 0.2 m/s: 100 s (MRPT's stepping drove 0.24-0.30 m/s at
        // sim_dt 0.001, 0.2022 at 0.05).
        const double speed = (b->x - a->x) / (b->t - a->t);
        EXPECT_NEAR(speed, 0.2, 1e-5) << "sim_dt " << dt;
        EXPECT_NEAR(b->y, 4.5, 1e-6) << "sim_dt " << dt;
        const auto s = readJson(out + "/summary.json");
        EXPECT_EQ(s["status"], "completed");
        // 26 m less the route's goal tolerance (0.08 m), at every sim_dt
        EXPECT_NEAR(s["distance_m"].get<double>(), 25.92, 0.005) << "sim_dt " << dt;
    }
}
