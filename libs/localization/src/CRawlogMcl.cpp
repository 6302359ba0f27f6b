#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>
#include <risknav/localization/CRawlogMcl.h>

#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

using namespace risknav::common;

namespace risknav::localization {
namespace {
std::string numbersText(const std::vector<double>& v) {
    std::string t;
    for (double x : v)
        t += (t.empty() ? "" : " ") + numberText(x);
    return t;
}
}  // namespace

void CRawlogMcl::TOptions::declare(Visitor& v) {
    v.integer(particles, "particles", TRange::closed(10, 1000000),
              "initial particles (>= 0.1 per KLD bin of the initial region)");
    v.choice(init, "init", {"pose", "global"},
             "pose: a box around init_pose; global: the whole map");
    // not v.pose(): this one has a default (0 0 0); the heading in degrees
    // in the file, radians held
    std::vector<double> pose{initPose.x, initPose.y, initPose.phi * 180 / M_PI};
    const auto poseBuilt = pose;
    v.numbers(pose, "init_pose", TRange::closed(-1e6, 1e6, "m"), "x [m] y [m] phi [deg]",
              TCount{0, 1, 3});
    if (pose != poseBuilt)
        initPose = {pose[0], pose[1], pose[2] * M_PI / 180};
    // "hx [hy]": one half-width for both, or one each
    std::vector<double> xy{init_xy, init_y};
    const auto xyBuilt = xy;
    v.numbers(xy, "init_xy", TRange::closed(0, 1000, "m"),
              "half-width of the initial box, or \"hx hy\"", TCount{1});
    // only a load reads more than it was handed (loadFromConfigFile() names
    // the file)
    if (xy.size() > 2)
        throw CConfigKeyError(section, "init_xy", numbersText(xy),
                              "needs one half-width, or x and y half-widths");
    if (xy != xyBuilt) {
        init_xy = xy[0];
        init_y = xy.size() == 2 ? xy[1] : xy[0];
    }
    v.number(init_phi_deg, "init_phi_deg", TRange::closed(0, 180, "deg"),
             "half-width of the initial heading range");
    v.number(lf_std_hit, "lf_std_hit", TRange::closed(0.001, 10, "m"),
             "likelihood field sigma");
    v.integer(lf_decimation, "lf_decimation", TRange::closed(1, 1000),
              "use every N-th laser ray");
    v.number(lf_max_corrs_distance, "lf_max_corrs_distance",
             TRange::closed(0.01, 10, "m"), "likelihood field correspondence distance");
}

CRawlogMcl::CRawlogMcl() {
    // pf-localization's defaults (localization_demo.ini).
    pfOptions.PF_algorithm = mrpt::bayes::CParticleFilter::pfStandardProposal;
    pfOptions.resamplingMethod = mrpt::bayes::CParticleFilter::prMultinomial;
    pfOptions.adaptiveSampleSize = true;
    pfOptions.BETA = 0.5;
    kldOptions.KLD_binSize_PHI = 10 * M_PI / 180;
    kldOptions.KLD_binSize_XY = 0.10;
    kldOptions.KLD_delta = 0.01;
    kldOptions.KLD_epsilon = 0.01;
    kldOptions.KLD_maxSampleSize = 40000;
    kldOptions.KLD_minSampleSize = 150;
    kldOptions.KLD_minSamplesPerBin = 0;
}

namespace {
// An MRPT enum key as MRPT's read_enum takes it: the name or its number.
int readEnum(const mrpt::config::CConfigFileBase& c, const std::string& s,
             const std::string& k, int def, const std::vector<std::string>& names) {
    const std::string t = trim(readString(c, s, k, ""));
    if (t.empty())
        return def;
    for (size_t i = 0; i < names.size(); i++)
        if (t == names[i] || t == std::to_string(i))
            return int(i);
    std::string all;
    for (size_t i = 0; i < names.size(); i++)
        all += (i ? ", " : "") + names[i] + " (" + std::to_string(i) + ")";
    throwBadKey(c, s, k, t, "must be one of: " + all);
}
}  // namespace

void CRawlogMcl::loadFromConfigFile(const mrpt::config::CConfigFileBase& c) {
    loadOptions(options, c, "Localization");
    obstacleRule.reset();
    if (c.sectionExists("World")) {
        mapping::TObstacleRule rule;
        loadOptions(rule, c, "World");
        obstacleRule = rule;
    }
    // MRPT's own loaders of these sections take "5abc" as 5, -1 particles as
    // 4e9 (a hang), KLD_delta 0 to an assert mid-run, and demand every key
    // of a [PF_options] given in part: MRPT's keys, read strictly, each
    // optional with pf-localization's default, each in its range.
    const std::string pf = "PF_options", kld = "KLD_options";
    using PF = mrpt::bayes::CParticleFilter;
    auto& o = pfOptions;
    o.PF_algorithm = PF::TParticleFilterAlgorithm(
        readEnum(c, pf, "PF_algorithm", int(o.PF_algorithm),
                 {"pfStandardProposal", "pfAuxiliaryPFStandard", "pfOptimalProposal",
                  "pfAuxiliaryPFOptimal"}));
    o.resamplingMethod = PF::TParticleResamplingAlgorithm(
        readEnum(c, pf, "resamplingMethod", int(o.resamplingMethod),
                 {"prMultinomial", "prResidual", "prStratified", "prSystematic"}));
    o.adaptiveSampleSize = readBool(c, pf, "adaptiveSampleSize", o.adaptiveSampleSize);
    o.BETA = readDouble(c, pf, "BETA", o.BETA, TRange::closed(0, 1));
    o.sampleSize = unsigned(readInt(c, pf, "sampleSize", int(o.sampleSize),
                                    TRange::closed(1, 1000000, "particles")));
    o.powFactor =
        readDouble(c, pf, "powFactor", o.powFactor, TRange{0, 1, true, false, ""});
    o.max_loglikelihood_dyn_range =
        readDouble(c, pf, "max_loglikelihood_dyn_range", o.max_loglikelihood_dyn_range,
                   TRange{0, 1e6, true, false, ""});
    o.pfAuxFilterOptimal_MaximumSearchSamples = unsigned(readInt(
        c, pf, "pfAuxFilterOptimal_MaximumSearchSamples",
        int(o.pfAuxFilterOptimal_MaximumSearchSamples), TRange::closed(1, 100000)));
    o.pfAuxFilterStandard_FirstStageWeightsMonteCarlo =
        readBool(c, pf, "pfAuxFilterStandard_FirstStageWeightsMonteCarlo",
                 o.pfAuxFilterStandard_FirstStageWeightsMonteCarlo);
    o.pfAuxFilterOptimal_MLE =
        readBool(c, pf, "pfAuxFilterOptimal_MLE", o.pfAuxFilterOptimal_MLE);
    auto& k = kldOptions;
    k.KLD_minSampleSize =
        unsigned(readInt(c, kld, "KLD_minSampleSize", int(k.KLD_minSampleSize),
                         TRange::closed(1, 1000000, "particles")));
    k.KLD_maxSampleSize =
        unsigned(readInt(c, kld, "KLD_maxSampleSize", int(k.KLD_maxSampleSize),
                         TRange::closed(1, 1000000, "particles")));
    if (k.KLD_maxSampleSize < k.KLD_minSampleSize)
        throwBadKey(c, kld, "KLD_maxSampleSize",
                    readString(c, kld, "KLD_maxSampleSize", ""),
                    "must be at least KLD_minSampleSize = " +
                        std::to_string(k.KLD_minSampleSize));
    k.KLD_binSize_XY = readDouble(c, kld, "KLD_binSize_XY", k.KLD_binSize_XY,
                                  TRange::closed(0.001, 100, "m"));
    k.KLD_binSize_PHI = readDegrees(c, kld, "KLD_binSize_PHI", k.KLD_binSize_PHI,
                                    TRange{0, 180, true, false, "deg"});
    k.KLD_delta =
        readDouble(c, kld, "KLD_delta", k.KLD_delta, TRange{0, 1, true, true, ""});
    k.KLD_epsilon =
        readDouble(c, kld, "KLD_epsilon", k.KLD_epsilon, TRange{0, 1, true, true, ""});
    k.KLD_minSamplesPerBin = readDouble(c, kld, "KLD_minSamplesPerBin",
                                        k.KLD_minSamplesPerBin, TRange::closed(0, 1e6));
}

void CRawlogMcl::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    options.saveToConfigFile(c, "Localization");
    pfOptions.saveToConfigFile(c, "PF_options");
    // MRPT 2.5.8's TKLDParams cannot save itself: its keys, as it reads them.
    const std::string k = "KLD_options";
    writeKey(c, k, "KLD_binSize_XY", kldOptions.KLD_binSize_XY);
    writeDegrees(c, k, "KLD_binSize_PHI", kldOptions.KLD_binSize_PHI);  // read in degrees
    writeKey(c, k, "KLD_delta", kldOptions.KLD_delta);
    writeKey(c, k, "KLD_epsilon", kldOptions.KLD_epsilon);
    writeKey(c, k, "KLD_minSampleSize", int(kldOptions.KLD_minSampleSize));
    writeKey(c, k, "KLD_maxSampleSize", int(kldOptions.KLD_maxSampleSize));
    writeKey(c, k, "KLD_minSamplesPerBin", kldOptions.KLD_minSamplesPerBin);
}

double CRawlogMcl::initialBins(const mrpt::maps::COccupancyGridMap2D& grid) const {
    // The cells resetUniformFreeSpace() draws from, by its own index rule.
    const bool global = options.init == "global";
    const auto& p = options.initPose;
    const int sx = int(grid.getSizeX()), sy = int(grid.getSizeY());
    int x1 = 0, x2 = sx - 1, y1 = 0, y2 = sy - 1;
    if (!global) {
        const double xmin = p.x - options.init_xy, xmax = p.x + options.init_xy;
        const double ymin = p.y - options.init_y, ymax = p.y + options.init_y;
        if (xmin > grid.getXMin())
            x1 = std::max(0, grid.x2idx(xmin));
        if (xmax < grid.getXMax())
            x2 = std::min(sx - 1, grid.x2idx(xmax));
        if (ymin > grid.getYMin())
            y1 = std::max(0, grid.y2idx(ymin));
        if (ymax < grid.getYMax())
            y2 = std::min(sy - 1, grid.y2idx(ymax));
    }
    size_t free = 0;
    for (int x = x1; x <= x2; x++)
        for (int y = y1; y <= y2; y++)
            if (grid.getCell(x, y) >= 0.7)
                free++;
    const double res = grid.getResolution();
    const double area = double(free) * res * res;
    const double phiRange =
        global ? 2 * M_PI : std::min(2 * M_PI, 2 * options.init_phi_deg * M_PI / 180);
    const auto& k = kldOptions;
    return std::max(1.0, area / (k.KLD_binSize_XY * k.KLD_binSize_XY)) *
           std::max(1.0, phiRange / k.KLD_binSize_PHI);
}

int CRawlogMcl::minParticles(const mrpt::maps::COccupancyGridMap2D& grid) const {
    return int(std::max(10.0, std::ceil(kMinParticlesPerBin * initialBins(grid))));
}

void CRawlogMcl::checkParticles(const mrpt::maps::COccupancyGridMap2D& grid) const {
    const int n = minParticles(grid);
    if (options.particles >= n)
        return;
    std::ostringstream why;
    why << "must be in [" << n << ", 1e+06] for init = " << options.init
        << " on this map (" << kMinParticlesPerBin
        << " per KLD bin of the initial region: " << std::llround(initialBins(grid))
        << " bins); fewer lose the robot and every frame then draws KLD_maxSampleSize";
    throw common::CConfigKeyError("Localization", "particles",
                                  std::to_string(options.particles), why.str());
}

namespace {
// The grid as the observation model takes it under `rule`: the surface of
// its obstacles (obstacle cells next to one that is not) at P(free) 0 (MRPT's
// likelihood field counts P(free) < 0.5), every other cell at least 0.5 (no
// obstacle to the field; cells of P(free) >= 0.7 stay free space for
// resetUniformFreeSpace()), and with outside_is_obstacle a ring of obstacle
// cells around it (as the simulator's CRayCastMap: resizeGrid keeps the cells
// where they are, the bounds being whole cells). A return comes from an
// obstacle's surface: the field measures a point's distance to the nearest
// surface, so a pose that puts points deep inside a solid region (a SLAM
// map's unknown outside, a thick wall) is as unlikely as one that puts them
// in the open. With every obstacle cell kept, MRPT's field rated such a pose
// a perfect fit: on the Malaga campus a filter slid 0.3 m along a corridor
// into the grey outside with the same likelihood as the true pose.
mrpt::maps::COccupancyGridMap2D echoGrid(const mrpt::maps::COccupancyGridMap2D& map,
                                         const mapping::TObstacleRule& rule) {
    mrpt::maps::COccupancyGridMap2D g(map);
    if (rule.outside_is_obstacle) {
        const float r = map.getResolution();
        g.resizeGrid(map.getXMin() - r, map.getXMax() + r, map.getYMin() - r,
                     map.getYMax() + r, 0.0f, false);
    }
    using Cell = mrpt::maps::COccupancyGridMap2D::cellType;
    const Cell wall = mrpt::maps::COccupancyGridMap2D::p2l(0.0f),
               half = mrpt::maps::COccupancyGridMap2D::p2l(0.5f);
    const int nx = int(g.getSizeX()), ny = int(g.getSizeY());
    const int ox = rule.outside_is_obstacle ? 1 : 0;  // map cell = cell - ox
    const int mx = int(map.getSizeX()), my = int(map.getSizeY());
    std::vector<uint8_t> obst(size_t(nx) * ny);
    for (int cy = 0; cy < ny; cy++)
        for (int cx = 0; cx < nx; cx++) {
            const int sx = cx - ox, sy = cy - ox;
            const bool onMap = sx >= 0 && sy >= 0 && sx < mx && sy < my;
            obst[size_t(cy) * nx + cx] =
                onMap ? rule.isObstacle(map.getCell(sx, sy)) : rule.outside_is_obstacle;
        }
    // An obstacle cell is a surface a return can come from when one of its
    // 8 neighbours is not an obstacle (beyond the grid: an obstacle).
    auto surface = [&](int cx, int cy) {
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                const int x = cx + dx, y = cy + dy;
                if (x >= 0 && y >= 0 && x < nx && y < ny && !obst[size_t(y) * nx + x])
                    return true;
            }
        return false;
    };
    for (int cy = 0; cy < ny; cy++) {
        Cell* row = g.getRow(cy);
        for (int cx = 0; cx < nx; cx++) {
            if (obst[size_t(cy) * nx + cx])
                row[cx] = surface(cx, cy) ? wall : half;
            else if (mrpt::maps::COccupancyGridMap2D::l2p(row[cx]) < 0.5f)
                row[cx] = half;
        }
    }
    return g;
}
}  // namespace

void CRawlogMcl::initialize(const mrpt::maps::COccupancyGridMap2D& grid, uint64_t seed) {
    // A whole new generator, not just randomize(): the old one may hold a
    // cached Gaussian draw, which would make a rawlog's result depend on the
    // rawlogs replayed before it in the same process.
    mrpt::random::getRandomGenerator() =
        mrpt::random::CRandomGenerator(static_cast<uint32_t>(seed));
    m_pdf = mrpt::slam::CMonteCarloLocalization2D();
    m_map = std::make_shared<mrpt::maps::COccupancyGridMap2D>(
        obstacleRule ? echoGrid(grid, *obstacleRule) : grid);
    m_fitField.reset();
    m_failedChecks = 0;
    m_converged = false;
    m_checksSinceReset = 0;
    auto& lo = m_map->likelihoodOptions;
    lo.likelihoodMethod = mrpt::maps::COccupancyGridMap2D::lmLikelihoodField_Thrun;
    lo.LF_stdHit = float(options.lf_std_hit);
    lo.LF_decimation = uint32_t(options.lf_decimation);
    lo.LF_maxCorrsDistance = float(options.lf_max_corrs_distance);
    m_pf.m_options = pfOptions;
    m_pdf.options.KLD_params = kldOptions;
    m_pdf.options.metricMap = m_map;
    // Particles only on free cells (as pf-localization's init_PDF_mode 0).
    try {
        if (options.init == "global")
            m_pdf.resetUniformFreeSpace(m_map.get(), 0.7, options.particles);
        else {
            const auto& p = options.initPose;
            const double dphi = options.init_phi_deg * M_PI / 180;
            m_pdf.resetUniformFreeSpace(m_map.get(), 0.7, options.particles,
                                        p.x - options.init_xy, p.x + options.init_xy,
                                        p.y - options.init_y, p.y + options.init_y,
                                        p.phi - dphi, p.phi + dphi);
        }
    } catch (const std::exception&) {
        throw common::CBadInputError(
            "[Localization] init_pose / init_xy: no free map cell in the initial box");
    }
}

TMclEstimate CRawlogMcl::step(const mrpt::obs::CActionCollection& actions,
                              const mrpt::obs::CSensoryFrame& sf) {
    mrpt::bayes::CParticleFilter::TParticleFilterStats stats;
    m_pf.executeOn(m_pdf, &actions, &sf, &stats);
    return estimate();
}

TMclEstimate CRawlogMcl::estimate() const {
    TMclEstimate e;
    const auto [cov, mean] = m_pdf.getCovarianceAndMean();
    e.mean = mean.asTPose();
    e.cov = cov;
    e.particles = m_pdf.size();
    e.ess = m_pdf.ESS();
    return e;
}

const mapping::CDistanceField& CRawlogMcl::fitField() const {
    if (!m_map)
        throw std::logic_error("CRawlogMcl: checkLost() before initialize()");
    if (!m_fitField) {
        // Obstacles as the afraid learner's scan-to-map test takes them:
        // occupied cells only (never-seen cells and the outside are no
        // surface a scan could have hit).
        mapping::TObstacleRule rule;
        rule.unknown_is_obstacle = rule.outside_is_obstacle = false;
        m_fitField = std::make_shared<const mapping::CDistanceField>(*m_map, rule);
    }
    return *m_fitField;
}

TLocalizationCheck CRawlogMcl::checkLocalization(
    const mrpt::obs::CObservation2DRangeScan* scan) const {
    const TMclEstimate e = estimate();
    const auto& o = lostOptions;
    TScanFit fit;
    if (scan)
        fit = scanMapFit(
            fitField(), *scan, e.mean, o.fit_distance,
            o.max_range > 0 ? o.max_range : std::numeric_limits<double>::infinity());
    auto c = judgeLocalization(fit, std::sqrt(std::max(0.0, e.cov(0, 0) + e.cov(1, 1))),
                               std::sqrt(std::max(0.0, e.cov(2, 2))) * 180 / M_PI, o);
    c.ess = e.ess;
    c.particles = e.particles;
    return c;
}

TLocalizationCheck CRawlogMcl::checkLost(const mrpt::obs::CSensoryFrame& sf,
                                         const std::string& scanLabel) {
    const auto scan = firstRangeScan(sf, scanLabel);
    auto c = checkLocalization(scan.get());
    const auto& o = lostOptions;
    m_checksSinceReset++;
    if (!m_converged && c.spreadXY <= o.max_spread_xy &&
        c.spreadPhiDeg <= o.max_spread_phi_deg)
        m_converged = true;
    if (!m_converged) {
        // still localizing since the last reset: no verdict until the grace
        // is over, then lost outright
        c.converging = m_checksSinceReset < o.converge_checks;
        c.failed = !c.converging;
        if (c.failed)
            c.reason = "not_converged";
        m_failedChecks = c.failed ? o.lost_after : 0;
    } else
        m_failedChecks = c.failed ? m_failedChecks + 1 : 0;
    c.consecutiveFailed = m_failedChecks;
    c.lost = m_failedChecks >= o.lost_after;
    return c;
}

void CRawlogMcl::recover(bool global) {
    if (!m_map)
        throw std::logic_error("CRawlogMcl: recover() before initialize()");
    const auto& o = lostOptions;
    const auto mean = estimate().mean;
    const size_t n = size_t(o.recovery_particles);
    bool done = false;
    if (!global) {
        const double dphi = o.recovery_phi_deg * M_PI / 180;
        try {
            m_pdf.resetUniformFreeSpace(m_map.get(), 0.7, n, mean.x - o.recovery_xy,
                                        mean.x + o.recovery_xy, mean.y - o.recovery_xy,
                                        mean.y + o.recovery_xy, mean.phi - dphi,
                                        mean.phi + dphi);
            done = true;
        } catch (const std::exception&) {
            // no free cell in the box (a mean off the map): the whole map
        }
    }
    if (!done)
        m_pdf.resetUniformFreeSpace(m_map.get(), 0.7, n);
    m_failedChecks = 0;
    m_converged = false;
    m_checksSinceReset = 0;
}

}  // namespace risknav::localization
