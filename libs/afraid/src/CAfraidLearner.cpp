#include <risknav/afraid/CAfraidLearner.h>
#include <risknav/afraid/afraid_level.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CProgress.h>
#include <risknav/common/config_read.h>
#include <risknav/common/stopping.h>
#include <risknav/localization/CRawlogReader.h>
#include <risknav/localization/scan_fit.h>

#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose2D.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>

#include <sys/stat.h>

using namespace risknav::common;
namespace fs = std::filesystem;

namespace risknav::afraid {
namespace {
// The same file twice (one path twice, a symbolic or a hard link to it)
// would count its experience twice: files are compared by identity, the
// device and inode numbers.
void checkDistinctFiles(const std::string& section, const std::string& key,
                        const std::vector<std::string>& files) {
    std::map<std::pair<dev_t, ino_t>, size_t> seen;
    for (size_t i = 0; i < files.size(); i++) {
        struct stat st {};
        if (::stat(files[i].c_str(), &st) != 0)
            continue;  // (reported as not found)
        const auto [it, fresh] = seen.emplace(std::make_pair(st.st_dev, st.st_ino), i);
        checkRule(fresh, section, key, files[i],
                  "entry " + std::to_string(i + 1) +
                      " given twice: the same file as entry " +
                      std::to_string(it->second + 1) + " '" + files[it->second] +
                      "' (the same path, or a link to it); its experience would "
                      "count twice");
    }
}

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

void CAfraidLearner::TOptions::declare(Visitor& v) {
    v.include(map);
    v.include(obstacles);
    // From the config, relative to it (the command line's are added by the learner).
    v.paths(rawlogs, "rawlogs",
            "rawlogs to learn from (more on the command line); each must exist");
    v.paths(afraid_in, "afraid_in", "earlier .afraid files to add up; each once");
    v.text(afraid_name, "afraid_name", false,
           "the learned file: a name ending in .afraid");
    v.paths(groundtruth_files, "groundtruth_file",
            "optional \"t x y phi\" files, one per rawlog in the same order");
    v.text(scan_label, "scan_label", false,
           "sensorLabel of the scan ('' = the first 2D scan of each frame)");
    v.number(match_distance, "match_distance", TRange::closed(0.01, 5, "m"),
             "a scan point this close to a map obstacle agrees with the map");
    v.number(min_match, "min_match", TRange::closed(0, 1),
             "frames with a smaller agreeing fraction are not localized");
    v.number(diverged_fraction, "diverged_fraction", TRange::closed(0, 1),
             "more non-localized frames than this: MCL diverged");
    v.include(krr);
    v.number(sample_bin, "sample_bin", TRange::closed(0.01, 10, "m"),
             "passes and events are pooled in squares this size");
    v.number(zone_threshold, "zone_threshold", {0, 1e6, true, false, "events per pass"},
             "level above which a cell is in a zone");
    v.number(v_max, "v_max", {0, 10, true, false, "m/s"}, "speed outside the zones");
    v.number(v_safe, "v_safe", {0, 10, true, false, "m/s"}, "speed inside the zones");
    v.seed(seed, "seed", "particle filter seed (with each rawlog's name and size)");
}

void CAfraidLearner::TOptions::validateRules() const {
    const std::string& s = section;
    // Without rawlogs, a merge-only run of the afraid_in files.
    checkRule(!rawlogs.empty() || !afraid_in.empty(), s, "rawlogs", "",
              "no rawlog: give [" + s + "] rawlogs or RAWLOG arguments (or afraid_in " +
                  "files to merge only)");
    // (fileProblem() also tells a FIFO or device from a missing file, and
    // notes the file as an input of the run)
    auto problem = [](const std::string& f, const std::string& what = "file") {
        const std::string why = fileProblem(f);
        return why == "not found" ? what + " not found" : why;
    };
    for (const auto& r : rawlogs)
        checkRule(fileProblem(r).empty(), s, "rawlogs", r, problem(r, "rawlog"));
    checkDistinctFiles(s, "rawlogs", rawlogs);
    for (const auto& a : afraid_in)
        checkRule(fileProblem(a).empty(), s, "afraid_in", a, problem(a));
    checkDistinctFiles(s, "afraid_in", afraid_in);
    checkRule(afraid_name.find('/') == std::string::npos && afraid_name.size() >= 8 &&
                  endsWith(afraid_name, ".afraid"),
              s, "afraid_name", afraid_name, "must be a file name ending in .afraid");
    // after a partial replay the file is <name>.partial.afraid
    checkOutputFileName(
        s, "afraid_name", afraid_name,
        afraid_name.substr(0, afraid_name.size() - 7) + ".partial.afraid");
    for (const auto& g : groundtruth_files)
        checkRule(fileProblem(g).empty(), s, "groundtruth_file", g, problem(g));
    // One ground truth per rawlog, in the same order: a second rawlog must not
    // be scored against the first one's truth.
    checkRule(groundtruth_files.empty() || groundtruth_files.size() == rawlogs.size(), s,
              "groundtruth_file", joinPathList(groundtruth_files),
              "needs one file per rawlog (" + std::to_string(rawlogs.size()) +
                  " rawlogs, " + std::to_string(groundtruth_files.size()) +
                  " ground-truth files)");
    checkRule(v_safe <= v_max, s, "v_safe", numberText(v_safe), "must be <= v_max");
}

void CAfraidLearner::loadFromConfigFile(const CIniConfig& c,
                                        const std::vector<std::string>& extra,
                                        std::optional<uint64_t> seedOverride) {
    for (const auto& s : c.sections())
        if (s != "AfraidLearn" && s != "Robot" && s != "AfraidDetector" &&
            s != "Localization" && s != "PF_options" && s != "KLD_options")
            c.throwUnknownSection(s,
                                  "AfraidLearn, Robot, AfraidDetector, "
                                  "Localization, PF_options, KLD_options");
    try {
        options.loadFromConfigFile(c, "AfraidLearn");
        // Command-line rawlogs are relative to the working directory: made
        // absolute, so that config_effective.ini names them from anywhere.
        for (const auto& r : extra)
            options.rawlogs.push_back(fs::absolute(r).lexically_normal().string());
        if (seedOverride)
            options.seed = *seedOverride;
        options.validate();
        detector.loadFromConfigFile(c);
        mcl.loadFromConfigFile(c);
        c.throwOnUnreadKeys();
        prepare();
    } catch (const CConfigKeyError& e) {
        throw CBadInputError(configWhere(c, e.section, e.key) + typedValueMessage(c, e));
    }
}

void CAfraidLearner::saveToConfigFile(mrpt::config::CConfigFileBase& c) const {
    options.saveToConfigFile(c, options.section);
    detector.saveToConfigFile(c);
    mcl.saveToConfigFile(c);
}

void CAfraidLearner::validate() const {
    options.validate();
    detector.validate();
    mcl.options.validate();
}

void CAfraidLearner::prepare() {
    validate();
    m_map = loadOccupancyGrid(options.map);
    // Too few start particles for the initial region lose the robot, and a
    // lost filter runs at KLD_maxSampleSize: refused before the replay.
    if (!options.rawlogs.empty())
        mcl.checkParticles(m_map);
    // Which cells are obstacles, and every cell's distance to the nearest one:
    // the map side of the scan-to-map agreement.
    m_field = mapping::CDistanceField(m_map, options.obstacles);
    m_new = CAfraidGrid(m_map);
    // The earlier files, added up one at a time (integer counts: the sum does
    // not depend on the order).
    m_old = CAfraidGrid(m_map);
    for (const auto& file : options.afraid_in) {
        CAfraidGrid g;
        try {
            g = CAfraidGrid::load(file);
        } catch (const std::exception& e) {
            throw CBadInputError(e.what());
        }
        if (!g.sameGeometry(m_new))
            throw CBadInputError(file + ": learned on another map (" + g.geometryText() +
                                 "; this map: " + m_new.geometryText() + ")");
        m_old.merge(g);
    }
    m_gt.clear();
    for (const auto& file : options.groundtruth_files) {
        const auto& gt = m_gt.emplace_back(readGroundTruth(file));
        checkRule(!gt.empty(), options.section, "groundtruth_file", file,
                  "no 't x y phi' lines");
    }
}

double CAfraidLearner::scanMapAgreement(const mrpt::obs::CObservation2DRangeScan& scan,
                                        const mrpt::math::TPose2D& pose) const {
    // On the surface of a map obstacle: near it from outside, and not deep
    // inside it; a point off the map is no evidence either way, whatever the
    // rule says of the outside (else a scan into the void would agree).
    const auto fit =
        localization::scanMapFit(m_field, scan, pose, options.match_distance);
    return fit.points ? fit.fraction() : 0.0;
}

void CAfraidLearner::run(bool quiet) {
    const auto& o = options;
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < o.rawlogs.size() && m_error.empty(); i++) {
        m_processed.push_back(o.rawlogs[i]);
        const size_t matchedBefore = m_errN;
        replay(o.rawlogs[i], m_gt.empty() ? nullptr : &m_gt[i], quiet);
        if (!m_gt.empty() && m_errN == matchedBefore && m_error.empty() && m_sawScan)
            throw CBadInputError(o.groundtruth_files[i] +
                                 ": no line's time matches a frame of " + o.rawlogs[i] +
                                 " (within 0.05 s): the ground truth of another run?");
    }
    m_replaySeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!o.rawlogs.empty() && !m_sawScan && m_error.empty())
        throw CBadInputError(
            o.rawlogs.front() + (o.rawlogs.size() > 1 ? " (and the others)" : "") +
            ": no 2D laser scan (CObservation2DRangeScan" +
            (o.scan_label.empty() ? std::string() : " labelled '" + o.scan_label + "'") +
            ") in the rawlog");
    m_new.frames = m_frames;
}

namespace {
// The 2D laser scan of a frame (the one labelled scanLabel, if given).
mrpt::obs::CObservation2DRangeScan::Ptr laserOf(const mrpt::obs::CSensoryFrame& sf,
                                                const std::string& scanLabel) {
    for (const auto& o : sf) {
        auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(o);
        if (s && (scanLabel.empty() || s->sensorLabel == scanLabel))
            return s;
    }
    return mrpt::obs::CObservation2DRangeScan::Ptr();
}

// Count the frames first (cheap: no filtering) for the progress line, and
// see whether the log holds the laser at all, before any work (exit 2,
// earlier outputs untouched): MRPT's range-bearing demo logs
// (kf-slam_demo, RO-SLAM_demo) were called "truncated at entry 500" for
// their last action, not what they are.
size_t countFramesWithScan(const std::string& path, const std::string& scanLabel) {
    size_t total = 0;
    bool anyScan = false;
    std::string countError;
    try {
        localization::CRawlogReader counter(path);
        while (const auto f = counter.next()) {
            total++;
            anyScan = anyScan || (f->sf && laserOf(*f->sf, scanLabel));
        }
    } catch (const std::exception& e) {
        countError = e.what();
    }
    if (!anyScan && (total > 0 || countError.empty())) {
        const std::string what =
            "no 2D laser scan (CObservation2DRangeScan" +
            (scanLabel.empty() ? std::string() : " labelled '" + scanLabel + "'") + ")";
        if (countError.empty())
            throw CBadInputError(path + ": " + what + " in the file (" +
                                 std::to_string(total) +
                                 " frames): nothing to localize with");
        else {
            // the reader's reason without its leading "<path>: "
            const std::string why = countError.rfind(path + ": ", 0) == 0
                                        ? countError.substr(path.size() + 2)
                                        : countError;
            throw CBadInputError(path + ": " + what + " in its first " +
                                 std::to_string(total) +
                                 " frames, where reading stops: " + why);
        }
    }
    return total;
}
}  // namespace

void CAfraidLearner::replay(const std::string& path,
                            const std::vector<TGroundTruthPose>* gt, bool quiet) {
    const size_t total = countFramesWithScan(path, options.scan_label);
    localization::CRawlogReader reader(path);
    CProgress progress("replay " + fs::path(path).filename().string(), total, "frames",
                       quiet);
    // A seed per rawlog that does not depend on the order of the rawlogs, so
    // that learning on A then B (resumed from A's .afraid) equals learning on
    // A and B in one run.
    // Name and size, not the full path: the same log gives the same result
    // wherever it is stored.
    std::error_code ec;
    const uint64_t size = fs::file_size(path, ec);
    mcl.initialize(m_map, options.seed ^ std::hash<std::string>{}(
                                             fs::path(path).filename().string() + "#" +
                                             std::to_string(size)));
    detector.reset();
    std::optional<mrpt::Clock::time_point> lastT;
    std::optional<mrpt::math::TPose2D> lastLocalized;
    size_t done = 0;
    while (true) {
        std::optional<localization::TRawlogFrame> frame;
        try {
            frame = reader.next();
        } catch (const std::exception& e) {
            m_error = e.what();
            break;
        }
        if (!frame)
            break;
        progress.update(++done);
        if (!frame->actions || !frame->sf)
            continue;
        const auto scan = laserOf(*frame->sf, options.scan_label);
        if (!scan)
            continue;
        m_sawScan = true;
        const auto est = mcl.step(*frame->actions, *frame->sf);
        // Speed from the odometry increment and the time since the last frame.
        double speed = 0;
        const auto t = scan->timestamp;
        if (auto mv =
                frame->actions->getActionByClass<mrpt::obs::CActionRobotMovement2D>();
            mv && lastT) {
            const double dt = mrpt::system::timeDifference(*lastT, t);
            const auto d = mv->poseChange->getMeanVal();
            if (dt > 1e-3)
                speed = std::hypot(d.x(), d.y()) / dt;
        }
        lastT = t;
        // Does the scan agree with the map at the estimated pose?
        const double match = scanMapAgreement(*scan, est.mean);
        const bool localized = match >= options.min_match;
        m_matchSum += match;
        m_frames++;
        const auto step = detector.step(*scan, est.mean, est.cov, speed, m_map, m_field);
        m_est.push_back({mrpt::Clock::toDouble(t), est.mean.x, est.mean.y, est.mean.phi,
                         est.cov(0, 0), est.cov(1, 1), match, est.particles, localized});
        if (localized) {
            m_localized++;
            m_new.addExposure(est.mean.x, est.mean.y);
            if (lastLocalized)
                m_new.addTraversal(lastLocalized->x, lastLocalized->y, est.mean.x,
                                   est.mean.y);
            else
                m_new.addPass(est.mean.x, est.mean.y);
            lastLocalized = est.mean;
            m_traj.emplace_back(est.mean.x, est.mean.y);
            if (step.afraid) {
                m_new.addRobotEvent(est.mean.x, est.mean.y);
                // Where the robot meets the obstacle on its way: the obstacle
                // projected onto the robot's line (on the path, whichever way
                // the robot comes; the robot's own cell if none was found).
                const auto onPath = step.obstacleFound ? mrpt::poses::CPose2D(est.mean) +
                                                             mrpt::poses::CPose2D(
                                                                 step.obstacleAlong, 0, 0)
                                                       : mrpt::poses::CPose2D(est.mean);
                m_new.addObstacleEvent(onPath.x(), onPath.y());
                TAfraidEvent e;
                e.t = mrpt::Clock::toDouble(t);
                e.rawlog = fs::path(path).filename().string();
                e.entry = frame->entry;
                e.robotX = est.mean.x;
                e.robotY = est.mean.y;
                e.robotPhi = est.mean.phi;
                e.obstacleFound = step.obstacleFound;
                e.obstacleX = step.obstacleX;
                e.obstacleY = step.obstacleY;
                e.diff = step.diff;
                e.speed = step.speed;
                e.obsCur = step.obsCur;
                e.obsPredict = step.obsPredict;
                m_events.push_back(e);
            }
        }
        if (gt) {
            const double tt = mrpt::Clock::toDouble(t);
            const auto it = std::lower_bound(
                gt->begin(), gt->end(), tt,
                [](const TGroundTruthPose& g, double v) { return g[0] < v; });
            for (auto g : {it, it == gt->begin() ? it : it - 1})
                if (g != gt->end() && std::abs((*g)[0] - tt) < 0.05) {
                    const double err =
                        std::hypot((*g)[1] - est.mean.x, (*g)[2] - est.mean.y);
                    m_errSum += err;
                    m_errMax = std::max(m_errMax, err);
                    m_errN++;
                    break;
                }
        }
    }
    progress.finish();
    m_new.runs++;
}

bool CAfraidLearner::diverged() const {
    return m_frames > 0 &&
           1.0 - double(m_localized) / double(m_frames) > options.diverged_fraction;
}

void CAfraidLearner::generalize() {
    // This run's experience plus the earlier files'. Every count (and runs,
    // frames) is a sum, and each rawlog's replay depends only on the rawlog
    // (its filter seed on its name and size, the detector and the filter reset
    // per rawlog): one .afraid per rawlog, merged in any order, equals one run
    // over all of them, byte for byte.
    m_grid = m_new;
    if (!options.afraid_in.empty())
        m_grid.merge(m_old);
    m_level = afraidLevel(m_grid, options.krr, options.sample_bin);
    const auto& rb = detector.robot;
    m_zones = findZones(
        m_level, m_grid, options.zone_threshold,
        common::stoppingDistance(options.v_max, rb.t_delay, rb.decel) + rb.radius);
}

double CAfraidLearner::levelAt(double x, double y) const {
    const int cx = m_grid.xToCol(x), cy = m_grid.yToRow(y);
    return m_grid.inside(cx, cy) && !m_level.empty()
               ? m_level[size_t(cy) * m_grid.sizeX() + cx]
               : 0.0;
}

}  // namespace risknav::afraid
