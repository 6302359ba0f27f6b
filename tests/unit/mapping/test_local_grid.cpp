// M1 mapping (Miura et al. 2006, section 2): Bayes update, N, classification,
// fusion and the scrolling local grid.
#include <risknav/mapping/CLocalProbGrid.h>
#include <risknav/mapping/fast_atan2.h>
#include <risknav/mapping/free_space.h>

#include <gtest/gtest.h>

#include <map>

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace risknav::mapping;

namespace {
TSensorModel laserModel() {
    TSensorModel m;
    m.p_obs_given_obstacle = 0.7;
    m.p_obs_given_free = 0.3;
    m.range_uncertainty = 0.05;
    return m;
}

/** A scan of `beams` rays over `fovDeg` from `robot` (sensor at the robot
 * centre) against the vertical wall x = wallX (no return beyond maxRange). */
mrpt::obs::CObservation2DRangeScan wallScan(const mrpt::math::TPose2D& robot,
                                            double wallX, int beams = 181,
                                            double fovDeg = 180, double maxRange = 8) {
    mrpt::obs::CObservation2DRangeScan s;
    s.aperture = float(fovDeg * M_PI / 180);
    s.maxRange = float(maxRange);
    s.rightToLeft = true;
    s.resizeScan(size_t(beams));
    for (int k = 0; k < beams; k++) {
        const double a = robot.phi - 0.5 * s.aperture + k * s.aperture / (beams - 1);
        const double c = std::cos(a);
        const double r = c > 1e-9 ? (wallX - robot.x) / c : 1e9;
        const bool hit = r > 0 && r < maxRange;
        s.setScanRange(size_t(k), float(hit ? r : maxRange));
        s.setScanRangeValidity(size_t(k), hit);
    }
    return s;
}
}  // namespace

TEST(SensorModel, BayesUpdateByHand) {
    TSensorModel m;                                                       // 0.6 / 0.45
    EXPECT_NEAR(bayesUpdate(0.5, true, m), 0.3 / (0.3 + 0.225), 1e-12);   // 0.5714
    EXPECT_NEAR(bayesUpdate(0.5, false, m), 0.2 / (0.2 + 0.275), 1e-12);  // 0.4211
    // two free readings = odds (0.4/0.55)^2
    const double p2 = bayesUpdate(bayesUpdate(0.5, false, m), false, m);
    const double odds = std::pow(0.4 / 0.55, 2);
    EXPECT_NEAR(p2, odds / (1 + odds), 1e-12);
    // an occupied reading after a free one returns to 0.5 only if the model is
    // symmetric; this one is not
    EXPECT_NE(bayesUpdate(bayesUpdate(0.5, false, m), true, m), 0.5);
}

TEST(SensorModel, NecessaryObservationsFromTheModel) {
    EXPECT_EQ(necessaryObservations(TSensorModel{}, 0.2), 5);  // the paper's N
    EXPECT_EQ(necessaryObservations(laserModel(), 0.2), 2);    // 0.3, then 0.155
    TSensorModel weak;
    weak.p_obs_given_obstacle = 0.55;
    weak.p_obs_given_free = 0.45;  // odds x 0.818 per reading: 7 to pass 0.25
    EXPECT_EQ(necessaryObservations(weak, 0.2), 7);
    EXPECT_EQ(necessaryObservations(TSensorModel{}, 0.45), 1);
    TSensorModel useless;
    useless.p_obs_given_obstacle = 0.4;
    useless.p_obs_given_free = 0.5;
    EXPECT_THROW(necessaryObservations(useless, 0.2), std::invalid_argument);
    EXPECT_THROW(useless.validate(), std::exception);
}

TEST(LocalGrid, Classification) {
    EXPECT_EQ(classifyCell(0.71f, 3, 0.7, 0.2), TCellClass::Obstacle);
    EXPECT_EQ(classifyCell(0.7f, 3, 0.7, 0.2), TCellClass::UndecidedObserved);
    EXPECT_EQ(classifyCell(0.19f, 3, 0.7, 0.2), TCellClass::Free);
    EXPECT_EQ(classifyCell(0.5f, 0, 0.7, 0.2), TCellClass::UndecidedUnobserved);
    EXPECT_EQ(classifyCell(0.5f, 1, 0.7, 0.2), TCellClass::UndecidedObserved);
}

TEST(LocalGrid, FusionTruthTable) {
    using C = TCellClass;
    using F = TFusedCell;
    const C all[] = {C::Obstacle, C::Free, C::UndecidedObserved, C::UndecidedUnobserved};
    // rows a, columns b, in the order above
    const F expected[4][4] = {
        {F::Obstacle, F::Obstacle, F::Obstacle, F::Obstacle},
        {F::Obstacle, F::Free, F::Free, F::Undecided},
        {F::Obstacle, F::Free, F::Undecided, F::Undecided},
        {F::Obstacle, F::Undecided, F::Undecided, F::Undecided},
    };
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            EXPECT_EQ(fuseCells(all[a], all[b]), expected[a][b]) << a << " " << b;
}

TEST(LocalGrid, FuseGridsIsClassifyAndFuseCellByCell) {
    // fuseGrids() computes the classes without branches, comparing floats
    // with the thresholds' nearest floats: the same as classifyCell() +
    // fuseCells() on every cell, the thresholds' edges (the floats nearest
    // each threshold, above and below) included, for thresholds that are
    // floats (0.75, 0.25) and that are not (0.7, 0.2, ...)
    std::mt19937 rng(5);
    const int n = 64;
    for (const auto& [occ, fr] : std::vector<std::pair<double, double>>{
             {0.7, 0.2}, {0.75, 0.25}, {0.6, 0.4}, {0.55, 0.1}, {0.9999, 0.0001}}) {
        CLocalProbGrid a(n, 0.05, 0, 0), b(n, 0.05, 0, 0);
        std::vector<float> edges = {0.5f, 0.001f, 0.999f};
        for (const double t : {occ, fr}) {
            const float f = float(t);
            edges.insert(edges.end(),
                         {f, std::nextafter(f, 0.f), std::nextafter(f, 1.f)});
        }
        std::uniform_real_distribution<float> u(0.f, 1.f);
        std::uniform_int_distribution<int> pick(0, 2 * int(edges.size())), count(0, 2);
        for (auto* g : {&a, &b})
            for (int j = 0; j < n; j++)
                for (int i = 0; i < n; i++) {
                    const size_t r = size_t(pick(rng));
                    g->setCell(i, j, r < edges.size() ? edges[r] : u(rng),
                               uint16_t(count(rng)));
                }
        const auto m = fuseGrids(a, b, occ, fr);
        int byClass[3] = {0, 0, 0};
        for (size_t k = 0; k < m.cells.size(); k++) {
            const auto expected =
                fuseCells(classifyCell(a.probabilities()[k], a.counts()[k], occ, fr),
                          classifyCell(b.probabilities()[k], b.counts()[k], occ, fr));
            ASSERT_EQ(m.cells[k], expected) << k << " " << occ << " " << fr;
            byClass[int(expected)]++;
        }
        for (int c : byClass)
            EXPECT_GT(c, 100);  // every fused class occurs
    }
}

TEST(LocalGrid, SectorModelFreeBeforeOccupiedAroundNothingBeyond) {
    CLocalProbGrid g(200, 0.05);
    const mrpt::math::TPose2D robot(0.02, 0.02, 0);
    const auto scan = wallScan(robot, 2.0);
    const auto m = laserModel();
    g.integrateScan(robot, scan, m);
    const int j = g.y2idx(0.02);
    // straight ahead: R = 1.98 m, delta 0.05
    EXPECT_NEAR(g.probability(g.x2idx(1.0), j), 0.3, 1e-6);  // free reading
    EXPECT_NEAR(g.probability(g.x2idx(2.0), j), 0.7, 1e-6);  // occupied reading
    EXPECT_NEAR(g.probability(g.x2idx(2.3), j), 0.5, 1e-6);  // beyond R_max: untouched
    EXPECT_EQ(g.observations(g.x2idx(2.3), j), 0);
    EXPECT_EQ(g.observations(g.x2idx(1.0), j), 1);            // one reading per scan
    EXPECT_NEAR(g.probability(g.x2idx(-1.0), j), 0.5, 1e-6);  // behind a 180 deg sensor
    // every cell within the field of view and nearer than the wall is read
    for (int i = g.x2idx(0.3); i < g.x2idx(1.8); i++)
        for (int jj = g.y2idx(-1.0); jj < g.y2idx(1.0); jj++)
            EXPECT_EQ(g.observations(i, jj), 1) << i << " " << jj;
}

TEST(LocalGrid, EgoMotionKeepsAWallInPlace) {
    // The robot drives and turns; the grid scrolls with it. After 40 cycles
    // the obstacle cells are still exactly the wall x = 3 (one cell thick).
    CLocalProbGrid g(200, 0.05);
    const auto m = laserModel();
    mrpt::math::TPose2D robot(0.01, 0.01, 0.0);
    int scrolled = 0;
    for (int k = 0; k < 40; k++) {
        const auto sh = g.recenter(robot.x, robot.y);
        scrolled += std::abs(sh.first) + std::abs(sh.second);
        g.integrateScan(robot, wallScan(robot, 3.0), m);
        robot.x += 0.037;
        robot.y += 0.021 * std::sin(0.3 * k);
        robot.phi = 0.4 * std::sin(0.2 * k);
    }
    EXPECT_GT(scrolled, 20);
    int obstacles = 0;
    for (int j = 0; j < g.size(); j++)
        for (int i = 0; i < g.size(); i++)
            if (classifyCell(g.probability(i, j), g.observations(i, j), 0.7, 0.2) ==
                TCellClass::Obstacle) {
                obstacles++;
                EXPECT_NEAR(g.idx2x(i), 3.0, 0.05) << g.idx2y(j);
            }
    EXPECT_GT(obstacles, 60);  // > 3 m of wall
    // the robot is in the centre cell
    EXPECT_EQ(g.x2idx(robot.x - 0.037), g.size() / 2);
}

TEST(LocalGrid, RecenterMovesContentByWholeCells) {
    CLocalProbGrid g(10, 0.5);  // [-2.5, 2.5)
    g.setCell(g.x2idx(1.2), g.y2idx(-0.3), 0.9f, 4);
    g.recenter(1.6, 0.1);
    EXPECT_FLOAT_EQ(g.probability(g.x2idx(1.2), g.y2idx(-0.3)), 0.9f);
    EXPECT_EQ(g.observations(g.x2idx(1.2), g.y2idx(-0.3)), 4);
    EXPECT_EQ(g.x2idx(1.6), 5);
    g.recenter(-20, 0);  // everything scrolls out
    for (float p : g.probabilities())
        EXPECT_FLOAT_EQ(p, 0.5f);
}

TEST(LocalGrid, RecenterKeepsEveryCellAtItsWorldPlace) {
    // every cell against its world position, for shifts in all directions,
    // beyond the grid included
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> pr(0.01f, 0.99f);
    for (const auto& [mx, my] : std::vector<std::pair<double, double>>{
             {0.3, 0.0}, {-0.45, 0.2}, {0.0, -0.6}, {1.2, 1.3}, {-2.0, -2.4}, {7, 0}}) {
        CLocalProbGrid g(12, 0.1, 0.0, 0.0);
        std::map<std::pair<int, int>, std::pair<float, uint16_t>> world;  // cm -> cell
        auto key = [&](int i, int j) {
            return std::pair{int(std::lround(g.idx2x(i) * 100)),
                             int(std::lround(g.idx2y(j) * 100))};
        };
        for (int j = 0; j < 12; j++)
            for (int i = 0; i < 12; i++) {
                const float p = pr(rng);
                const auto n = uint16_t(rng() % 50);
                g.setCell(i, j, p, n);
                world[key(i, j)] = {p, n};
            }
        g.recenter(mx, my);
        for (int j = 0; j < 12; j++)
            for (int i = 0; i < 12; i++) {
                const auto it = world.find(key(i, j));
                const float p = it == world.end() ? 0.5f : it->second.first;
                const uint16_t n = it == world.end() ? 0 : it->second.second;
                ASSERT_EQ(g.probability(i, j), p)
                    << mx << " " << my << " " << i << " " << j;
                ASSERT_EQ(g.observations(i, j), n);
            }
    }
}

TEST(LocalGrid, ProbabilitiesStayClampedSoANewObjectShowsQuickly) {
    CLocalProbGrid g(100, 0.05);
    const auto m = laserModel();
    const mrpt::math::TPose2D robot(0.025, 0.025, 0);  // a cell centre
    for (int k = 0; k < 200; k++)
        g.integrateScan(robot, wallScan(robot, 100.0, 181, 180, 2), m);  // all free
    const int i = g.x2idx(1.625), j = g.y2idx(0.025);
    EXPECT_FLOAT_EQ(g.probability(i, j), float(CLocalProbGrid::kProbabilityMin));
    int readings = 0;
    while (readings < 50 &&
           classifyCell(g.probability(i, j), 1, 0.7, 0.2) != TCellClass::Obstacle) {
        g.integrateScan(robot, wallScan(robot, 1.625), m);  // a wall through that cell
        readings++;
    }
    EXPECT_LE(readings, 5);
}

namespace {
/** The sector model of integrateScan, plainly: every cell in range, its own
 * bearing's ray, one reading (the reference for the tiled version). */
void bruteForceScan(std::vector<float>& p, std::vector<uint16_t>& count,
                    const CLocalProbGrid& g, const mrpt::math::TPose2D& robot,
                    const mrpt::obs::CObservation2DRangeScan& scan,
                    const TSensorModel& m) {
    const size_t n = scan.getScanSize();
    const auto& sp = scan.sensorPose;
    const double c = std::cos(robot.phi), s = std::sin(robot.phi);
    const double sx = robot.x + c * sp.x() - s * sp.y();
    const double sy = robot.y + s * sp.x() + c * sp.y();
    const double syaw = robot.phi + sp.yaw();
    const double step = n > 1 ? scan.aperture / double(n - 1) : scan.aperture;
    const double reach = scan.maxRange + m.delta(scan.maxRange);
    for (int j = 0; j < g.size(); j++)
        for (int i = 0; i < g.size(); i++) {
            const double dx = g.idx2x(i) - sx, dy = g.idx2y(j) - sy;
            const double r = std::sqrt(dx * dx + dy * dy);
            if (r > reach)
                continue;
            const double b = (scan.rightToLeft ? 1.0 : -1.0) *
                             mrpt::math::wrapToPi(std::atan2(dy, dx) - syaw);
            long ray = long(std::round((b + 0.5 * scan.aperture) / step));
            if (scan.aperture >= 2 * M_PI - 1e-9)
                ray = ((ray % long(n)) + long(n)) % long(n);
            if (ray < 0 || ray >= long(n))
                continue;
            int reading = -1;
            if (scan.getScanRangeValidity(size_t(ray))) {
                const double R = scan.getScanRange(size_t(ray)), d = m.delta(R);
                reading = r < R - d ? 0 : (r <= R + d ? 1 : -1);
            } else if (r < scan.maxRange) {
                reading = 0;
            }
            if (reading < 0)
                continue;
            const size_t k = size_t(j) * size_t(g.size()) + size_t(i);
            p[k] = float(std::clamp(bayesUpdate(p[k], reading == 1, m),
                                    CLocalProbGrid::kProbabilityMin,
                                    1.0 - CLocalProbGrid::kProbabilityMin));
            count[k]++;
        }
}
/** `rays` valid rays over `aperture` [rad], ray k reading `even` [m] for
 * even k and `odd` for odd k (neighbours that read a cell differently). */
mrpt::obs::CObservation2DRangeScan alternatingScan(size_t rays, double aperture,
                                                   float maxRange, bool rightToLeft,
                                                   float even, float odd) {
    mrpt::obs::CObservation2DRangeScan scan;
    scan.aperture = float(aperture);
    scan.maxRange = maxRange;
    scan.rightToLeft = rightToLeft;
    scan.resizeScan(rays);
    for (size_t k = 0; k < rays; k++) {
        scan.setScanRange(k, k % 2 ? odd : even);
        scan.setScanRangeValidity(k, true);
    }
    return scan;
}
}  // namespace

// The tiled integrateScan (rays per tile, tiles beyond every reading skipped)
// must give every cell exactly the reading of the plain per-cell model: random
// scans (180 / 270 / 360 deg, either ray order, gaps, returns beyond maxRange,
// the sensor off-centre and turned, near the grid's edge and outside it).
TEST(LocalProbGrid, TiledScanEqualsThePlainSectorModel) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    TSensorModel m = laserModel();
    m.range_uncertainty_quad = 0.01;
    int updatedCells = 0;
    for (int trial = 0; trial < 60; trial++) {
        const double fov = trial % 3 == 0 ? 360 : (trial % 3 == 1 ? 180 : 270);
        const int beams = 30 + int(u(rng) * 300);
        mrpt::obs::CObservation2DRangeScan scan;
        scan.aperture = float(fov * M_PI / 180);
        scan.maxRange = float(2 + 8 * u(rng));
        scan.rightToLeft = trial % 2 == 0;
        scan.sensorPose = mrpt::poses::CPose3D(0.3 * u(rng), 0.2 * (u(rng) - 0.5), 0.3,
                                               M_PI * (u(rng) - 0.5), 0, 0);
        scan.resizeScan(size_t(beams));
        for (int k = 0; k < beams; k++) {
            const double roll = u(rng);
            scan.setScanRange(size_t(k), float(roll < 0.1 ? scan.maxRange * 1.2
                                                          : 0.2 + roll * scan.maxRange));
            scan.setScanRangeValidity(size_t(k), roll > 0.05);
        }
        const int cells = 40 + int(u(rng) * 120);
        CLocalProbGrid g(cells, 0.05, 0, 0);
        const double half = 0.5 * cells * 0.05;
        const mrpt::math::TPose2D robot(
            trial % 7 == 0 ? 1.5 * half : (u(rng) - 0.5) * half, (u(rng) - 0.5) * half,
            2 * M_PI * (u(rng) - 0.5));
        std::vector<float> p(g.probabilities());
        std::vector<uint16_t> count(g.counts());
        bruteForceScan(p, count, g, robot, scan, m);
        g.integrateScan(robot, scan, m);
        for (size_t k = 0; k < p.size(); k++) {
            ASSERT_EQ(g.counts()[k], count[k]) << "trial " << trial << " cell " << k;
            ASSERT_EQ(g.probabilities()[k], p[k]) << "trial " << trial << " cell " << k;
            updatedCells += count[k] > 0;
        }
    }
    EXPECT_GT(updatedCells, 50000);  // the scans did read many cells
    // Every ray a valid return beyond maxRange (R - delta > maxRange +
    // delta(maxRange)): cells beyond that reach get no reading, also where
    // whole tiles lie nearer than every ray's free bound.
    for (int trial = 0; trial < 4; trial++) {
        const auto scan = alternatingScan(181, trial < 2 ? M_PI : 2 * M_PI, 2.0f,
                                          trial % 2 == 0, 3.5f, 3.6f);
        CLocalProbGrid g(160, 0.05, 0, 0);
        const mrpt::math::TPose2D robot(0.013, -0.021, 0.3 * trial);
        std::vector<float> p(g.probabilities());
        std::vector<uint16_t> count(g.counts());
        bruteForceScan(p, count, g, robot, scan, m);
        g.integrateScan(robot, scan, m);
        for (size_t k = 0; k < p.size(); k++) {
            ASSERT_EQ(g.counts()[k], count[k])
                << "beyond trial " << trial << " cell " << k;
            ASSERT_EQ(g.probabilities()[k], p[k]) << "beyond trial " << trial;
        }
    }
    // Cells a hair off a sector boundary (the scan turned so that the
    // boundary between its two rays passes 1e-10-3e-8 rad from a cell's
    // bearing, either side): the fast first guess of the ray can land on the
    // wrong side there, and the exact formula must decide.
    int boundaryCases = 0;
    for (int trial = 0; trial < 40; trial++) {
        // the two rays read a cell at 1 m differently
        const auto scan = alternatingScan(2, M_PI, 3.0f, trial % 2 == 0, 1.0f, 2.0f);
        CLocalProbGrid g(60, 0.05, 0, 0);
        const int ci = 30 + int(u(rng) * 20) - 10, cj = 30 + int(u(rng) * 20) - 10;
        const double sx = g.idx2x(30) + 0.013, sy = g.idx2y(30) - 0.007;
        const double bearing = std::atan2(g.idx2y(cj) - sy, g.idx2x(ci) - sx);
        const double off[] = {1e-10, -1e-10, 3e-9, -3e-9, 1e-8, -1e-8, 3e-8, -3e-8};
        // the boundary (b = 0) at the cell's bearing + off
        const mrpt::math::TPose2D robot(sx, sy, bearing + off[trial % 8]);
        std::vector<float> p(g.probabilities());
        std::vector<uint16_t> count(g.counts());
        bruteForceScan(p, count, g, robot, scan, m);
        g.integrateScan(robot, scan, m);
        for (size_t k = 0; k < p.size(); k++) {
            ASSERT_EQ(g.counts()[k], count[k]) << "boundary trial " << trial;
            ASSERT_EQ(g.probabilities()[k], p[k]) << "boundary trial " << trial;
        }
        boundaryCases++;
    }
    EXPECT_EQ(boundaryCases, 40);
    // The same along a row: 181 rays alternately reading 1 m and 2 m, a
    // cell at ~1.5 m a hair off the boundary between two of them (the row
    // walk's cross products decide at 3e-9 rad and beyond, the exact formula
    // nearer); its reading (free, or none) shows which ray it got.
    int walkCases = 0;
    for (int trial = 0; trial < 96; trial++) {
        const auto scan = alternatingScan(181, M_PI, 3.0f, trial % 2 == 0, 1.0f, 2.0f);
        const double step = double(scan.aperture) / 180, sign = scan.rightToLeft ? 1 : -1;
        CLocalProbGrid g(100, 0.05, 0, 0);
        const double sx = g.idx2x(50) + 0.011, sy = g.idx2y(50) - 0.006;
        const int ci = 50 + int(u(rng) * 60) - 30, cj = 50 + int(u(rng) * 60) - 30;
        if (std::hypot(g.idx2x(ci) - sx, g.idx2y(cj) - sy) < 0.5)
            continue;
        const double bearing = std::atan2(g.idx2y(cj) - sy, g.idx2x(ci) - sx);
        const double off[] = {1e-10, -1e-10, 2e-9, -2e-9, 3e-9, -3e-9, 3e-8, -3e-8};
        const long k = 60 + long(u(rng) * 60);  // the boundary between rays k and k + 1
        // every third trial with an unwrapped yaw of ~2e7 rad, which the
        // exact formula rounds by ~1e-9 rad
        const double turns = trial % 3 == 2 ? 2 * M_PI * 3.5e6 : 0.0;
        const double syaw = bearing - sign * ((double(k) + 0.5) * step - 0.5 * M_PI) +
                            off[trial % 8] + turns;
        const mrpt::math::TPose2D robot(sx, sy, syaw);
        std::vector<float> p(g.probabilities());
        std::vector<uint16_t> count(g.counts());
        bruteForceScan(p, count, g, robot, scan, laserModel());
        g.integrateScan(robot, scan, laserModel());
        for (size_t c = 0; c < p.size(); c++) {
            ASSERT_EQ(g.counts()[c], count[c]) << "walk trial " << trial;
            ASSERT_EQ(g.probabilities()[c], p[c]) << "walk trial " << trial;
        }
        walkCases++;
    }
    EXPECT_GT(walkCases, 60);
    // A found case: an unwrapped yaw of -2.2e7 rad, where the exact formula
    // rounds the cell at (0.475, -2.875) from the sensor, 1e-9 rad off the
    // edge between rays 37 and 38 of 1440, into ray 38 (without the walk's
    // margin for the yaw's rounding the walk put it in 37)
    {
        // ray 37 reads the cell free, ray 38 does not reach it
        const auto scan = alternatingScan(1440, 2 * M_PI, 5.0f, true, 2.0f, 4.0f);
        CLocalProbGrid g(200, 0.05, 0, 0);  // cell centres at odd multiples of 0.025
        const mrpt::math::TPose2D robot(0, 0, -21964016.210175823);
        std::vector<float> p(g.probabilities());
        std::vector<uint16_t> count(g.counts());
        bruteForceScan(p, count, g, robot, scan, laserModel());
        g.integrateScan(robot, scan, laserModel());
        const int i = g.x2idx(0.475), j = g.y2idx(-2.875);
        EXPECT_EQ(g.counts()[g.index(i, j)], 0);  // ray 38's 2 m: not read
        for (size_t c = 0; c < p.size(); c++) {
            ASSERT_EQ(g.counts()[c], count[c]) << "huge yaw, cell " << c;
            ASSERT_EQ(g.probabilities()[c], p[c]) << "huge yaw, cell " << c;
        }
    }
}

// The bound integrateScan's fast path relies on: the polynomial atan2 within
// kFastAtan2MaxError / 2 of libm's, on a dense sweep of directions and on
// random points of every scale, the axes and the octant edges included.
TEST(FastAtan2, WithinItsBoundOfLibm) {
    double worst = 0;
    for (int k = 0; k <= 2000000; k++) {
        const double a = -M_PI + 2 * M_PI * k / 2000000.0;
        const double x = std::cos(a), y = std::sin(a);
        worst = std::max(worst, std::fabs(fastAtan2(y, x) - std::atan2(y, x)));
    }
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1), e(-8, 3);
    for (int k = 0; k < 200000; k++) {
        const double s = std::pow(10.0, e(rng));
        const double x = s * u(rng), y = s * u(rng);
        worst = std::max(worst, std::fabs(fastAtan2(y, x) - std::atan2(y, x)));
    }
    for (const double v : {1.0, -1.0, 0.0})
        for (const double w : {1.0, -1.0, 0.0})
            worst = std::max(worst, std::fabs(fastAtan2(v, w) - std::atan2(v, w)));
    EXPECT_LT(worst, 0.5 * kFastAtan2MaxError);
    EXPECT_GT(worst, 1e-9);  // it is an approximation: the fallback matters
}
