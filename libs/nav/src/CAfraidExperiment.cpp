#include <risknav/afraid/CAfraidLearner.h>
#include <risknav/afraid/afraid_speed.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CCsvWriter.h>
#include <risknav/common/CPlotImage.h>
#include <risknav/common/config_read.h>
#include <risknav/common/summary_json.h>
#include <risknav/nav/CAfraidExperiment.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CNavigationRun.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/nav/navigate_report.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

using namespace risknav::common;
using mrpt::math::TPoint2D;
using nlohmann::json;
namespace fs = std::filesystem;

namespace risknav::nav {
namespace {
const char* kSec = "AfraidExperiment";
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

json numOrNull(double x) {
    return std::isfinite(x) ? json(x) : json(nullptr);
}

struct TRunFigures {
    double sectionTime = kNaN;  ///< [s] first pass through the section (+axis)
    int doorCollisions = 0, collisions = 0, nearMisses = 0, insideStopping = 0;
    int emergences = 0;  ///< people who burst out of a door during the run
    std::string status;
    double time = 0;
};

// Time of the first pass through [s0, s1] along the axis, in the +axis
// direction, interpolated between cycles.
double sectionTime(const TNavRunResult& r, const afraid::TRouteAxis& a, double s0,
                   double s1) {
    double tIn = kNaN;
    for (size_t i = 1; i < r.cycles.size(); i++) {
        const auto& p = r.cycles[i - 1].truePose;
        const auto& q = r.cycles[i].truePose;
        const double u = a.along(p.x, p.y) + a.offset(),
                     v = a.along(q.x, q.y) + a.offset();
        auto cross = [&](double s) {
            return r.cycles[i - 1].t +
                   (s - u) / (v - u) * (r.cycles[i].t - r.cycles[i - 1].t);
        };
        if (std::isnan(tIn) && u < s0 && v >= s0)
            tIn = cross(s0);
        else if (!std::isnan(tIn) && u < s1 && v >= s1)
            return cross(s1) - tIn;
    }
    return kNaN;
}

TRunFigures figures(const TNavRunResult& r, const afraid::TRouteAxis& a, double s0,
                    double s1) {
    TRunFigures f;
    f.sectionTime = sectionTime(r, a, s0, s1);
    for (const auto& e : r.safety.events())
        if (e.kind == "collision" && e.object.rfind("DoorPedestrian", 0) == 0)
            f.doorCollisions++;
    f.collisions = r.collisions();
    f.nearMisses = r.safety.nearMisses();
    f.insideStopping = int(r.safety.corridorEntries().size());
    for (const auto& e : r.agentEvents)
        f.emergences += e.kind == "emerge";
    f.status = r.status;
    f.time = r.time;
    return f;
}

struct TStat {
    double mean = kNaN, lo = kNaN, hi = kNaN;
    int n = 0;
};
TStat stat(const std::vector<double>& v) {
    TStat s;
    double sum = 0;
    for (double x : v)
        if (std::isfinite(x)) {
            sum += x;
            s.lo = s.n ? std::min(s.lo, x) : x;
            s.hi = s.n ? std::max(s.hi, x) : x;
            s.n++;
        }
    if (s.n)
        s.mean = sum / s.n;
    return s;
}
std::string statText(const TStat& s, int decimals) {
    if (!s.n)
        return "-";
    char b[96];
    std::snprintf(b, sizeof(b), "%.*f [%.*f, %.*f]", decimals, s.mean, decimals, s.lo,
                  decimals, s.hi);
    return b;
}
std::string fmt(double v, int decimals) {
    if (!std::isfinite(v))
        return "-";
    char b[48];
    std::snprintf(b, sizeof(b), "%.*f", decimals, v);
    return b;
}
}  // namespace

void TAfraidExperimentOptions::declare(Visitor& v) {
    // whole numbers held: read as numbers, checked and converted here (an
    // empty list is refused, not the default seeds)
    std::vector<double> list(seeds.begin(), seeds.end());
    const auto built = list;
    const TRange range = TRange::closed(0, kMaxSeed);
    v.numbers(list, "seeds", range, "one run of each mode per seed, 1 to 100, distinct",
              TCount{1});
    if (list != built) {  // only a load reads other values (a CConfigKeyError
                          // here is named with the file by the loader)
        std::string text;
        for (double x : list)
            text += (text.empty() ? "" : " ") + numberText(x);
        seeds.clear();
        for (double x : list) {
            if (!range.contains(x))
                throw CConfigKeyError(section, "seeds", text,
                                      "'" + numberText(x) + "' " + range.describe());
            if (x != std::floor(x))
                throw CConfigKeyError(section, "seeds", text, "seeds are whole numbers");
            seeds.push_back(uint64_t(x));
        }
    }
    v.integer(learning_laps, "learning_laps", TRange::closed(1, 100, "laps"),
              "laps of the route at v_safe (back and forth)");
    v.integer(test_laps, "test_laps", TRange::closed(1, 100, "laps"),
              "laps at v_max, with and without the limiter");
    v.number(v_safe, "v_safe", TRange::closed(0.05, 5, "m/s"), "the learning speed");
    v.number(v_max, "v_max", TRange::closed(0.05, 5, "m/s"), "the fast speed");
    v.number(section_length, "section_length", TRange::closed(0.5, 1000, "m"),
             "the compared door section");
    v.number(lead_in, "lead_in", TRange::closed(0, 100, "m"),
             "the section starts this far before the first zone");
}

void TAfraidExperimentOptions::validateRules() const {
    const std::string& s = section;
    checkRule(!seeds.empty() && seeds.size() <= 100, s, "seeds",
              std::to_string(seeds.size()) + " seeds", "1 to 100 seeds");
    // the same run twice would count twice in the statistics
    std::string list;
    for (auto x : seeds)
        list += (list.empty() ? "" : " ") + std::to_string(x);
    for (size_t i = 0; i < seeds.size(); i++)
        checkRule(
            std::find(seeds.begin(), seeds.begin() + i, seeds[i]) == seeds.begin() + i, s,
            "seeds", list, "seed " + std::to_string(seeds[i]) + " is listed twice");
    checkRule(v_safe <= v_max, s, "v_safe", numberText(v_safe), "must be <= v_max");
}

namespace {
/** The experiment's configuration, loaded and checked once for all seeds. */
struct TExperiment {
    TAfraidExperimentOptions xo;
    std::vector<std::string>
        baseLimiters;  ///< the limiters of every run but the afraid one
    CNavigationRun nr;
    CAfraidSpeedLimiter::TOptions lo;  ///< the limiter's options (its file: learned)
    afraid::CAfraidLearner proto;      ///< the detector's and MCL's options
};

/** One seed's three runs, its learned map and its compared section. */
struct TSeedRuns {
    TNavRunResult rl, rw, ro;  ///< learning, with and without the limiter
    std::optional<afraid::CAfraidLearner> learner;
    afraid::TRouteAxis axis;
    double s0 = kNaN, s1 = kNaN;  ///< [m] the section along the axis
    TRunFigures fl, fw, fo;
};

/** The tallies over all seeds. */
struct TTotals {
    json perSeed = json::array();
    std::vector<double> tSafe, tWith, tWithout, speedup;
    int doorWith = 0, doorWithout = 0, stopWith = 0, stopWithout = 0;
};

const std::vector<std::string> kOwnSections = {kSec,           "AfraidDetector",
                                               "Localization", "PF_options",
                                               "KLD_options",  "CAfraidSpeedLimiter"};

void loadExperiment(const TAppContext& ctx, TExperiment& x) {
    CIniConfig& c = ctx.cfg;
    TAfraidExperimentOptions& xo = x.xo;
    loadOptions(xo, c, kSec);
    if (ctx.args.seed)
        xo.seeds = {*ctx.args.seed};
    const std::vector<std::string>& own = kOwnSections;
    // Before the navigator loads them (it would ask for the learned file):
    // the navigator's own parse of the list.
    CRiskAwareReactiveNav::TOptions navOptions;
    navOptions.loadFromConfigFile(c, "CRiskAwareReactiveNav");
    x.baseLimiters = navOptions.speed_limiters;
    for (const auto& n : x.baseLimiters)
        if (n.find("CAfraidSpeedLimiter") != std::string::npos)
            throwBadKey(c, "CRiskAwareReactiveNav", "speed_limiters", n,
                        "the experiment adds CAfraidSpeedLimiter itself (with the map "
                        "it learns); list only the other limiters");
    x.nr.loadFromConfigFile(c, ctx.args.seed, own);
    // The limiter's options (its file is the one learned here).
    CAfraidSpeedLimiter::TOptions& lo = x.lo;
    lo.krr.section = "CAfraidSpeedLimiter";
    lo.loadFromConfigFile(c, "CAfraidSpeedLimiter");
    if (c.hasKey("CAfraidSpeedLimiter", "afraid_file"))
        throwBadKey(c, "CAfraidSpeedLimiter", "afraid_file", lo.afraid_file,
                    "in an experiment the afraid map is the one learned; remove the key");
    lo.afraid_file = "learned";
    try {
        lo.validate();
    } catch (const CConfigKeyError& e) {
        throw CBadInputError(configWhere(c, e.section, e.key) + typedValueMessage(c, e));
    }
    x.proto.detector.loadFromConfigFile(c);
    x.proto.mcl.loadFromConfigFile(c);
    c.throwOnUnreadKeys(own);
}

/** One seed's runs: learning laps at v_safe, the afraid map learned from
 * them, test laps at v_max with the learned limiter and without it. */
void runSeed(const TAppContext& ctx, TExperiment& x, COutputDir& out,
             const std::string& scratch, uint64_t seed, bool first, TSeedRuns& s) {
    const TAfraidExperimentOptions& xo = x.xo;
    CNavigationRun& nr = x.nr;
    const auto& lo = x.lo;
    const std::string tag = "seed " + std::to_string(seed);
    // 1. Learning laps at v_safe, recorded.
    TNavRunSetup learn;
    learn.seed = seed;
    learn.maxSpeed = xo.v_safe;
    learn.limiters = x.baseLimiters;
    learn.laps = xo.learning_laps;
    learn.quiet = ctx.args.quiet;
    learn.label = "learn " + tag;
    // A name that does not depend on the process: the learner seeds its
    // particle filter from the rawlog's name and size (the staged output
    // name carries the PID), so that runs are reproducible.
    learn.rawlogPath = scratch + "/learning_seed" + std::to_string(seed) + ".rawlog";
    learn.groundtruthPath = scratch + "/gt_seed" + std::to_string(seed) + ".txt";
    s.rl = nr.run(learn);
    if (first) {
        fs::copy_file(learn.rawlogPath, out.stage("learning.rawlog"),
                      fs::copy_options::overwrite_existing);
        fs::copy_file(learn.groundtruthPath, out.stage("learning_groundtruth.txt"),
                      fs::copy_options::overwrite_existing);
    }
    // 2. The afraid map from that rawlog (MCL on the map, as risknav-afraid-learn).
    afraid::CAfraidLearner& learner = s.learner.emplace();
    learner.detector = x.proto.detector;
    learner.mcl.options = x.proto.mcl.options;
    learner.mcl.pfOptions = x.proto.mcl.pfOptions;
    learner.mcl.kldOptions = x.proto.mcl.kldOptions;
    learner.mcl.options.initPose = nr.options.start;
    learner.options.map = nr.world.mapSource;
    learner.options.rawlogs = {learn.rawlogPath};
    learner.options.groundtruth_files = {learn.groundtruthPath};
    learner.options.krr = lo.krr;
    learner.options.sample_bin = lo.sample_bin;
    learner.options.zone_threshold = lo.zone_threshold;
    learner.options.v_max = xo.v_max;
    learner.options.v_safe = xo.v_safe;
    learner.options.seed = seed;
    learner.prepare();
    learner.run(true);
    learner.generalize();
    const std::string afraidPath =
        first ? out.stage("learned.afraid")
              : scratch + "/learned_" + std::to_string(seed) + ".afraid";
    learner.grid().save(afraidPath);
    // 3. Test laps at v_max with the learned limiter and without it.
    TNavRunSetup with;
    with.seed = seed;
    with.maxSpeed = xo.v_max;
    with.limiters = x.baseLimiters;
    with.limiters->insert(with.limiters->begin(), "CAfraidSpeedLimiter");
    with.afraidFile = afraidPath;
    with.laps = xo.test_laps;
    with.quiet = ctx.args.quiet;
    with.label = "with limiter " + tag;
    const std::string navDir = scratch + "/navlog";
    if (first && nr.options.navlog)
        with.navlogDir = navDir;
    s.rw = nr.run(with);
    TNavRunSetup without = with;
    without.limiters = x.baseLimiters;
    without.afraidFile.reset();
    without.navlogDir.clear();
    without.label = "without limiter " + tag;
    s.ro = nr.run(without);
}

// The section: lead_in before the first zone on the learning run's axis.
void measureSection(const TExperiment& x, TSeedRuns& s) {
    const TAfraidExperimentOptions& xo = x.xo;
    std::vector<TPoint2D> traj;
    for (const auto& cy : s.rl.cycles)
        traj.emplace_back(cy.truePose.x, cy.truePose.y);
    s.axis = afraid::routeAxis(traj, 0.1);
    const auto& axis = s.axis;
    double zFirst = std::numeric_limits<double>::infinity();
    for (const auto& z : s.learner->zones())
        zFirst = std::min(zFirst, afraid::zoneSpan(z, axis).first);
    const double pos0 = axis.pos.front(), posLast = axis.pos.back();
    double s0 = kNaN, s1 = kNaN;
    if (std::isfinite(zFirst)) {
        // A run ends within goal_tolerance of the goal (the route's end):
        // the section ends before that, so that every run crosses its end,
        // and starts earlier than lead_in where needed to keep its length
        const double end = posLast - x.nr.options.goal_tolerance - 0.05;
        s0 = std::max(pos0, zFirst - xo.lead_in);
        if (s0 + xo.section_length > end)
            s0 = std::max(pos0, end - xo.section_length);
        s1 = std::min(s0 + xo.section_length, end);
    }
    s.s0 = s0;
    s.s1 = s1;
    s.fl = figures(s.rl, axis, s0, s1);
    s.fw = figures(s.rw, axis, s0, s1);
    s.fo = figures(s.ro, axis, s0, s1);
}

/** The seed's row of experiment.csv and its entry of summary.json. */
void tallySeed(uint64_t seed, const TSeedRuns& s, CCsvWriter& csv, TTotals& totals) {
    const TRunFigures &fl = s.fl, &fw = s.fw, &fo = s.fo;
    const double s0 = s.s0, s1 = s.s1;
    const afraid::CAfraidLearner& learner = *s.learner;
    const double up = fl.sectionTime / fw.sectionTime;
    totals.tSafe.push_back(fl.sectionTime);
    totals.tWith.push_back(fw.sectionTime);
    totals.tWithout.push_back(fo.sectionTime);
    totals.speedup.push_back(up);
    totals.doorWith += fw.doorCollisions;
    totals.doorWithout += fo.doorCollisions;
    totals.stopWith += fw.insideStopping;
    totals.stopWithout += fo.insideStopping;
    csv.row({std::to_string(seed),
             CCsvWriter::num(s0),
             CCsvWriter::num(s1),
             CCsvWriter::num(fl.sectionTime),
             CCsvWriter::num(fw.sectionTime),
             CCsvWriter::num(fo.sectionTime),
             CCsvWriter::num(up),
             CCsvWriter::num(fl.sectionTime / fo.sectionTime),
             std::to_string(fw.doorCollisions),
             std::to_string(fo.doorCollisions),
             std::to_string(fw.collisions),
             std::to_string(fo.collisions),
             std::to_string(fw.insideStopping),
             std::to_string(fo.insideStopping),
             std::to_string(fw.nearMisses),
             std::to_string(fo.nearMisses),
             std::to_string(learner.zones().size()),
             std::to_string(learner.events().size()),
             CCsvWriter::num(learner.mclErrorMean()),
             fl.status,
             fw.status,
             fo.status});
    auto runJson = [&](const TRunFigures& f) {
        return json{{"section_time_s", numOrNull(f.sectionTime)},
                    {"door_collisions", f.doorCollisions},
                    {"collisions", f.collisions},
                    {"near_misses", f.nearMisses},
                    {"inside_stopping_distance", f.insideStopping},
                    {"emergences", f.emergences},
                    {"status", f.status},
                    {"time_s", f.time}};
    };
    totals.perSeed.push_back({{"seed", seed},
                              {"section", {numOrNull(s0), numOrNull(s1)}},
                              {"zones", learner.zones().size()},
                              {"afraid_events", learner.events().size()},
                              {"mcl_error_mean_m", numOrNull(learner.mclErrorMean())},
                              {"mcl_diverged", learner.diverged()},
                              {"learning", runJson(fl)},
                              {"with_limiter", runJson(fw)},
                              {"without_limiter", runJson(fo)},
                              {"speedup_with", numOrNull(up)}});
}

// The figure: speed vs axis position on the first outbound pass.
void plotSeed(const TSeedRuns& s, bool first, CPlotImage& plot) {
    const auto& axis = s.axis;
    auto series = [&](const TNavRunResult& r, const std::string& label, TRgb col) {
        std::vector<double> x, y;
        double prev = -1e300;
        for (const auto& cy : r.cycles) {
            const double p = axis.along(cy.truePose.x, cy.truePose.y) + axis.offset();
            if (p < prev - 0.5)
                break;  // turned back: the first pass is over
            prev = std::max(prev, p);
            x.push_back(p);
            y.push_back(cy.speed);
        }
        plot.addSeries(first ? label : "", x, y, col, first ? 2 : 1);
    };
    series(s.rl, "v_safe throughout (learning)", {120, 120, 120});
    series(s.ro, "v_max without the afraid limiter", {220, 30, 30});
    series(s.rw, "v_max with the learned afraid limiter", {0, 110, 220});
}

/** The first seed's run with the limiter in detail: navlog, tables, pictures. */
void writeFirstSeedOutputs(const CNavigationRun& nr, const TSeedRuns& s,
                           const std::string& tag, COutputDir& out, CPlotImage& plot) {
    const TNavRunResult& rw = s.rw;
    const afraid::CAfraidLearner& learner = *s.learner;
    if (std::isfinite(s.s0)) {
        plot.addVLine(s.s0, "section", {0, 150, 0});
        plot.addVLine(s.s1, "", {0, 150, 0});
    }
    if (!rw.navlogFile.empty())
        fs::rename(rw.navlogFile, out.stage("navigation.reactivenavlog"));
    writeCyclesCsv(rw, nr.options.start_time, out.stage("cycles.csv"));
    writeEventsCsv(rw, nr.options.start_time, out.stage("events.csv"));
    std::vector<uint8_t> mask;
    const auto& g = learner.grid();
    if (g.sizeX() == int(nr.world.grid().getSizeX()) &&
        g.sizeY() == int(nr.world.grid().getSizeY())) {
        mask.assign(size_t(g.sizeX()) * size_t(g.sizeY()), 0);
        for (const auto& z : learner.zones())
            for (int i : z.mask)
                mask[size_t(i)] = 1;
    }
    char title[300];
    std::snprintf(title, sizeof(title),
                  "risknav-navigate, %s, with the learned afraid limiter: %s, "
                  "section %.1f s (v_safe %.1f s), %d collisions",
                  tag.c_str(), rw.status.c_str(), s.fw.sectionTime, s.fl.sectionTime,
                  rw.collisions());
    drawTrajectory(nr, rw, title, out.stage("trajectory.png"),
                   mask.empty() ? nullptr : &mask);
    drawSpeedProfile(rw, title, out.stage("speed_profile.png"));
}

/** experiment.md: the per-seed table and the paper's figures. */
std::string experimentTable(const TTotals& totals) {
    const TStat sS = stat(totals.tSafe), sW = stat(totals.tWith),
                sO = stat(totals.tWithout), sU = stat(totals.speedup);
    std::ostringstream md;
    md << "| seed | section time at v_safe [s] | with the learned limiter [s] | speed-up "
          "| "
          "without (v_max) [s] | door collisions with / without | inside d_stop with / "
          "without |\n|---|---|---|---|---|---|---|\n";
    for (const auto& p : totals.perSeed)
        md << "| " << p["seed"].get<uint64_t>() << " | "
           << fmt(p["learning"]["section_time_s"].is_null()
                      ? kNaN
                      : p["learning"]["section_time_s"].get<double>(),
                  1)
           << " | "
           << fmt(p["with_limiter"]["section_time_s"].is_null()
                      ? kNaN
                      : p["with_limiter"]["section_time_s"].get<double>(),
                  1)
           << " | "
           << fmt(p["speedup_with"].is_null() ? kNaN : p["speedup_with"].get<double>(), 2)
           << "x | "
           << fmt(p["without_limiter"]["section_time_s"].is_null()
                      ? kNaN
                      : p["without_limiter"]["section_time_s"].get<double>(),
                  1)
           << " | " << p["with_limiter"]["door_collisions"].get<int>() << " / "
           << p["without_limiter"]["door_collisions"].get<int>() << " | "
           << p["with_limiter"]["inside_stopping_distance"].get<int>() << " / "
           << p["without_limiter"]["inside_stopping_distance"].get<int>() << " |\n";
    md << "| **mean [min, max]** | " << statText(sS, 1) << " | " << statText(sW, 1)
       << " | " << statText(sU, 2) << " | " << statText(sO, 1) << " | " << totals.doorWith
       << " / " << totals.doorWithout << " (total) | " << totals.stopWith << " / "
       << totals.stopWithout
       << " (total) |\n| paper (002 section 3) | 51.3 | 24.3 | 2.11x | - | 0 / - | - |\n";
    return md.str();
}

/** summary.json and the effective config, committed with the run. */
void commitExperiment(const TAppContext& ctx, const TExperiment& x, const TTotals& totals,
                      COutputDir& out) {
    const TAfraidExperimentOptions& xo = x.xo;
    const TStat sS = stat(totals.tSafe), sW = stat(totals.tWith),
                sO = stat(totals.tWithout), sU = stat(totals.speedup);
    json summary = summaryHeader(ctx, xo.seeds.front());
    auto statJson = [](const TStat& s) {
        return json{{"mean", numOrNull(s.mean)},
                    {"min", numOrNull(s.lo)},
                    {"max", numOrNull(s.hi)},
                    {"n", s.n}};
    };
    summary["experiment"] = "afraid";
    summary["seeds"] = xo.seeds;
    summary["per_seed"] = totals.perSeed;
    summary["section_time_v_safe_s"] = statJson(sS);
    summary["section_time_with_limiter_s"] = statJson(sW);
    summary["section_time_without_limiter_s"] = statJson(sO);
    summary["speedup_with_limiter"] = statJson(sU);
    summary["door_collisions_with_limiter"] = totals.doorWith;
    summary["door_collisions_without_limiter"] = totals.doorWithout;
    summary["inside_stopping_distance_with_limiter"] = totals.stopWith;
    summary["inside_stopping_distance_without_limiter"] = totals.stopWithout;
    summary["paper"] = {{"section_time_before_s", 51.3}, {"section_time_after_s", 24.3}};
    mrpt::config::CConfigFileMemory effective;
    xo.saveToConfigFile(effective, kSec);
    x.nr.saveToConfigFile(effective);
    {
        // without afraid_file: the experiment learns it (and refuses the key)
        mrpt::config::CConfigFileMemory l;
        x.lo.saveToConfigFile(l, "CAfraidSpeedLimiter");
        // (read back as text: the saved key names are padded, as MRPT's)
        copyConfigKeys(
            reparsedConfig(l), effective,
            [](const std::string&, const std::string& k) { return k == "afraid_file"; });
    }
    x.proto.detector.saveToConfigFile(effective);
    x.proto.mcl.saveToConfigFile(effective);
    commitRun(ctx, out, summary, effective);
    if (!ctx.args.quiet)
        std::fprintf(stderr,
                     "%s: speed-up %s, door collisions %d with / %d without -> %s\n",
                     ctx.info.name.c_str(), statText(sU, 2).c_str(), totals.doorWith,
                     totals.doorWithout, out.dir().c_str());
}
}  // namespace

void runAfraidExperiment(const TAppContext& ctx) {
    TExperiment x;
    loadExperiment(ctx, x);

    COutputDir out(ctx.args.outDir, ctx.info.name);
    // removed with the run's staging area, also by the next run after a kill
    const std::string scratch = out.scratchDir("experiment");

    TTotals totals;
    CCsvWriter csv(out.stage("experiment.csv"), {"seed",
                                                 "section_from_m",
                                                 "section_to_m",
                                                 "t_v_safe_s",
                                                 "t_with_s",
                                                 "t_without_s",
                                                 "speedup_with",
                                                 "speedup_without",
                                                 "door_collisions_with",
                                                 "door_collisions_without",
                                                 "collisions_with",
                                                 "collisions_without",
                                                 "inside_stopping_distance_with",
                                                 "inside_stopping_distance_without",
                                                 "near_misses_with",
                                                 "near_misses_without",
                                                 "zones",
                                                 "afraid_events",
                                                 "mcl_error_mean_m",
                                                 "status_learning",
                                                 "status_with",
                                                 "status_without"});
    CPlotImage plot;
    plot.setTitle(
        "risknav-navigate afraid experiment: speed along the corridor (first pass)");
    plot.setXLabel("position along the route axis [m]");
    plot.setYLabel("speed [m/s]");
    for (size_t k = 0; k < x.xo.seeds.size(); k++) {
        const uint64_t seed = x.xo.seeds[k];
        const bool first = k == 0;
        const std::string tag = "seed " + std::to_string(seed);
        TSeedRuns s;
        runSeed(ctx, x, out, scratch, seed, first, s);
        measureSection(x, s);
        tallySeed(seed, s, csv, totals);
        plotSeed(s, first, plot);
        if (first)
            writeFirstSeedOutputs(x.nr, s, tag, out, plot);
        if (!ctx.args.quiet)
            std::fprintf(stderr,
                         "%s: %s: section %.1f s at v_safe, %.1f s with the limiter "
                         "(%.2fx), %.1f s without; door collisions %d with, %d without\n",
                         ctx.info.name.c_str(), tag.c_str(), s.fl.sectionTime,
                         s.fw.sectionTime, totals.speedup.back(), s.fo.sectionTime,
                         s.fw.doorCollisions, s.fo.doorCollisions);
    }
    csv.close();
    plot.save(out.stage("experiment_speed.png"));
    out.writeText("experiment.md", experimentTable(totals));
    commitExperiment(ctx, x, totals, out);
}

}  // namespace risknav::nav
