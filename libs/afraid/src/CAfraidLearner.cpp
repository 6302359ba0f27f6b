#include <risknav/afraid/CAfraidLearner.h>
#include <risknav/afraid/afraid_level.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/CProgress.h>
#include <risknav/common/config_read.h>
#include <risknav/localization/CRawlogReader.h>

#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose2D.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

using namespace risknav::common;
namespace fs = std::filesystem;

namespace risknav::afraid {
void CAfraidLearner::loadFromConfigFile(const CIniConfig& c,
                                        const std::vector<std::string>& extra,
                                        std::optional<uint64_t> seedOverride) {
    for (const auto& s : c.sections())
        if (s != "AfraidLearn" && s != "Localization" && s != "PF_options" &&
            s != "KLD_options" && s != "AfraidDetector")
            throw CBadInputError(c.path() + ": unknown section [" + s +
                                 "] (known: AfraidLearn, Localization, PF_options, "
                                 "KLD_options, AfraidDetector)");
    const std::string A = "AfraidLearn";
    loadOptions(mapSource, c, A);
    // Rawlogs: from the config (relative to it) and the command line (relative to the
    // CWD).
    // Whitespace-separated; "double quotes" keep a path with spaces together.
    std::vector<std::string> listed;
    {
        const std::string v = readString(c, A, "rawlogs", "");
        std::string cur;
        bool quoted = false, have = false;
        for (char ch : v) {
            if (ch == '"') {
                quoted = !quoted;
                have = true;
            } else if (std::isspace(static_cast<unsigned char>(ch)) && !quoted) {
                if (have)
                    listed.push_back(cur);
                cur.clear();
                have = false;
            } else {
                cur += ch;
                have = true;
            }
        }
        if (quoted)
            throwBadKey(c, A, "rawlogs", v, "unbalanced double quote");
        if (have)
            listed.push_back(cur);
    }
    for (const auto& r : listed) {
        fs::path p(r);
        if (p.is_relative())
            p = fs::path(c.folder()) / p;
        rawlogs.push_back(p.lexically_normal().string());
    }
    rawlogs.insert(rawlogs.end(), extra.begin(), extra.end());
    if (rawlogs.empty())
        throw CBadInputError(
            c.path() + ": no rawlog: give [AfraidLearn] rawlogs or RAWLOG arguments");
    for (const auto& r : rawlogs)
        if (!fs::is_regular_file(r))
            throw CBadInputError(r + ": rawlog not found");
    afraidIn = readPath(c, A, "afraid_in", "", false);
    if (!afraidIn.empty() && !fs::is_regular_file(afraidIn))
        throwBadKey(c, A, "afraid_in", afraidIn, "file not found");
    afraidName = readString(c, A, "afraid_name", afraidName);
    if (afraidName.find('/') != std::string::npos || afraidName.size() < 8 ||
        afraidName.substr(afraidName.size() - 7) != ".afraid")
        throwBadKey(c, A, "afraid_name", afraidName,
                    "must be a file name ending in .afraid");
    groundTruth = readPath(c, A, "groundtruth_file", "", false);
    if (!groundTruth.empty() && !fs::is_regular_file(groundTruth))
        throwBadKey(c, A, "groundtruth_file", groundTruth, "file not found");
    scanLabel = readString(c, A, "scan_label", "");
    matchDistance =
        readDouble(c, A, "match_distance", matchDistance, TRange::closed(0.01, 5, "m"));
    minMatch = readDouble(c, A, "min_match", minMatch, TRange::closed(0, 1));
    divergedFraction =
        readDouble(c, A, "diverged_fraction", divergedFraction, TRange::closed(0, 1));
    krr.bandwidth = readDouble(c, A, "kernel_bandwidth", krr.bandwidth,
                               TRange::closed(0.01, 100, "m"));
    krr.lambda = readDouble(c, A, "kernel_lambda", krr.lambda, {0, 1e6, true, false, ""});
    krr.cutoff = readDouble(c, A, "kernel_cutoff", krr.cutoff,
                            TRange::closed(1, 10, "bandwidths"));
    sampleBin = readDouble(c, A, "sample_bin", sampleBin, TRange::closed(0.01, 10, "m"));
    zoneThreshold = readDouble(c, A, "zone_threshold", zoneThreshold,
                               {0, 1e6, true, false, "events per pass"});
    vMax = readDouble(c, A, "v_max", vMax, {0, 10, true, false, "m/s"});
    vSafe = readDouble(c, A, "v_safe", vSafe, {0, 10, true, false, "m/s"});
    if (vSafe > vMax)
        throwBadKey(c, A, "v_safe", std::to_string(vSafe), "must be <= v_max");
    seed = static_cast<uint64_t>(
        readDouble(c, A, "seed", double(seed), TRange::closed(0, 9007199254740992.0)));
    if (seedOverride) {
        seed = *seedOverride;
        c.recordEffective(A, "seed", std::to_string(seed));
    }
    loadOptions(detector.options, c, "AfraidDetector");
    mcl.loadFromConfigFile(c);
    c.throwOnUnreadKeys();

    m_map = loadOccupancyGrid(mapSource);
    m_new = CAfraidGrid(m_map);
    if (!afraidIn.empty()) {
        try {
            m_old = CAfraidGrid::load(afraidIn);
        } catch (const std::exception& e) {
            throw CBadInputError(e.what());
        }
        if (!m_old.sameGeometry(m_new))
            throw CBadInputError(afraidIn + ": learned on another map (" +
                                 m_old.geometryText() +
                                 "; this map: " + m_new.geometryText() + ")");
    }
    if (!groundTruth.empty()) {
        std::ifstream f(groundTruth);
        for (std::string line; std::getline(f, line);) {
            if (line.empty() || line[0] == '%' || line[0] == '#')
                continue;
            std::istringstream ls(line);
            std::array<double, 4> v{};
            if (ls >> v[0] >> v[1] >> v[2] >> v[3])
                m_gt.push_back(v);
        }
        if (m_gt.empty())
            throwBadKey(c, A, "groundtruth_file", groundTruth, "no 't x y phi' lines");
    }
    // Distance to the nearest map obstacle, for the scan-to-map agreement.
    const int sx = int(m_map.getSizeX()), sy = int(m_map.getSizeY());
    cv::Mat freeMask(sy, sx, CV_8UC1), dist;
    for (int y = 0; y < sy; y++)
        for (int x = 0; x < sx; x++)
            freeMask.at<uint8_t>(y, x) = m_map.getCell(x, y) < 0.5f ? 0 : 255;
    cv::distanceTransform(freeMask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    m_obstDist.assign(size_t(sx) * sy, 0.f);
    for (int y = 0; y < sy; y++)
        for (int x = 0; x < sx; x++)
            m_obstDist[size_t(y) * sx + x] = dist.at<float>(y, x) * m_map.getResolution();
}

void CAfraidLearner::run(bool quiet) {
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < rawlogs.size() && m_error.empty(); i++)
        replay(rawlogs[i], quiet);
    m_replaySeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!m_sawScan && m_error.empty())
        throw CBadInputError(
            rawlogs.front() + (rawlogs.size() > 1 ? " (and the others)" : "") +
            ": no 2D laser scan (CObservation2DRangeScan" +
            (scanLabel.empty() ? std::string() : " labelled '" + scanLabel + "'") +
            ") in the rawlog");
    m_new.frames = m_frames;
}

void CAfraidLearner::replay(const std::string& path, bool quiet) {
    // Count the frames first (cheap: no filtering) for the progress line.
    size_t total = 0;
    try {
        localization::CRawlogReader counter(path);
        while (counter.next())
            total++;
    } catch (const std::exception&) {
    }
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
    mcl.initialize(
        m_map, seed ^ std::hash<std::string>{}(fs::path(path).filename().string() + "#" +
                                               std::to_string(size)));
    detector.reset();
    std::optional<mrpt::Clock::time_point> lastT;
    size_t done = 0;
    const int sx = int(m_map.getSizeX());
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
        mrpt::obs::CObservation2DRangeScan::Ptr scan;
        for (const auto& o : *frame->sf) {
            auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(o);
            if (s && (scanLabel.empty() || s->sensorLabel == scanLabel)) {
                scan = s;
                break;
            }
        }
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
        const auto pts = CAfraidDetector::robotFramePoints(*scan);
        const mrpt::poses::CPose2D pose(est.mean);
        size_t agree = 0;
        for (const auto& p : pts) {
            const auto w = pose + mrpt::poses::CPose2D(p.x, p.y, 0);
            const int cx = m_map.x2idx(w.x()), cy = m_map.y2idx(w.y());
            if (cx >= 0 && cy >= 0 && cx < sx && cy < int(m_map.getSizeY()) &&
                m_obstDist[size_t(cy) * sx + cx] <= matchDistance)
                agree++;
        }
        const double match = pts.empty() ? 0.0 : double(agree) / pts.size();
        const bool localized = match >= minMatch;
        m_matchSum += match;
        m_frames++;
        const auto step = detector.step(*scan, est.mean, speed, m_map);
        m_est.push_back({mrpt::Clock::toDouble(t), est.mean.x, est.mean.y, est.mean.phi,
                         est.cov(0, 0), est.cov(1, 1), match, est.particles, localized});
        if (localized) {
            m_localized++;
            m_new.addExposure(est.mean.x, est.mean.y);
            m_traj.emplace_back(est.mean.x, est.mean.y);
            if (step.afraid) {
                m_new.addRobotEvent(est.mean.x, est.mean.y);
                if (step.obstacleFound)
                    m_new.addObstacleEvent(step.obstacleX, step.obstacleY);
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
        if (!m_gt.empty()) {
            const double tt = mrpt::Clock::toDouble(t);
            const auto it = std::lower_bound(
                m_gt.begin(), m_gt.end(), tt,
                [](const std::array<double, 4>& g, double v) { return g[0] < v; });
            for (auto g : {it, it == m_gt.begin() ? it : it - 1})
                if (g != m_gt.end() && std::abs((*g)[0] - tt) < 0.05) {
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
           1.0 - double(m_localized) / double(m_frames) > divergedFraction;
}

void CAfraidLearner::generalize() {
    m_grid = m_new;
    if (!afraidIn.empty())
        m_grid.merge(m_old);
    m_level = afraidLevel(m_grid, krr, sampleBin);
    m_zones = findZones(m_level, m_grid, zoneThreshold);
}

double CAfraidLearner::levelAt(double x, double y) const {
    const int cx = m_grid.xToCol(x), cy = m_grid.yToRow(y);
    return m_grid.inside(cx, cy) && !m_level.empty()
               ? m_level[size_t(cy) * m_grid.sizeX() + cx]
               : 0.0;
}

}  // namespace risknav::afraid
