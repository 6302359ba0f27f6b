#pragma once
#include <risknav/afraid/CAfraidDetector.h>
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/afraid/afraid_zones.h>
#include <risknav/afraid/ground_truth.h>
#include <risknav/afraid/kernel_regression.h>
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/CValidatedOptions.h>
#include <risknav/common/grid_io.h>
#include <risknav/localization/CRawlogMcl.h>
#include <risknav/mapping/CDistanceField.h>
#include <risknav/mapping/TObstacleRule.h>

#include <mrpt/maps/COccupancyGridMap2D.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace risknav::afraid {
/** The localization of one frame, for trajectory.csv. */
struct TTrajectoryPoint {
    double t = 0, x = 0, y = 0, phi = 0, covXX = 0, covYY = 0, agreement = 0;
    size_t particles = 0;
    bool localized = false;
};

/** One afraid event, for events.csv. */
struct TAfraidEvent {
    double t = 0;
    std::string rawlog;
    size_t entry = 0;
    double robotX = 0, robotY = 0, robotPhi = 0;
    bool obstacleFound = false;
    double obstacleX = 0, obstacleY = 0;
    double diff = 0, speed = 0;
    int obsCur = 0, obsPredict = 0;
};

/** Learns where obstacles burst out (Choi, Chung, Song (002), PAPER_NOTES M3):
 * replays rawlogs with MCL on a known map, detects afraid events, accumulates
 * them with the exposure in a CAfraidGrid (optionally starting from an
 * earlier .afraid file), generalizes by kernel ridge regression and finds the
 * zones. Sections [AfraidLearn] (options), [AfraidDetector] and [Robot]
 * (detector), [Localization] [PF_options] [KLD_options] (mcl); keys in
 * config/risknav-afraid-learn.ini. */
class CAfraidLearner {
  public:
    /** The [AfraidLearn] keys: the map, which of its cells are obstacles (for
     * the scan-to-map agreement), the inputs and outputs, and the learning. */
    struct TOptions : public common::CDeclaredOptions {
        common::TMapSourceOptions map;  ///< map_* keys
        /** occupied_threshold ... outside_is_obstacle. Here the rule says which
         * cells confirm a scan point, so unknown cells and the outside do not by
         * default (a scan into unexplored space is no evidence of a good pose). */
        mapping::TObstacleRule obstacles;
        /** Absolute paths; relative ones in the file resolve against its folder.
         * Whitespace-separated, "double quotes" keep a path with spaces. */
        std::vector<std::string> rawlogs;
        /** Earlier .afraid files to start from (key afraid_in, a list like
         * rawlogs; empty = none): all are added up (integer counts, so the order
         * does not matter), once each. With afraid_in, rawlogs may be empty: a
         * merge-only run (merge, generalize, report). */
        std::vector<std::string> afraid_in;
        std::string afraid_name = "learned.afraid";  ///< a file name ending in .afraid
        /** Optional "t x y phi" files for the MCL error (key groundtruth_file):
         * one per rawlog, in the same order. */
        std::vector<std::string> groundtruth_files;
        std::string scan_label;  ///< "" = the first 2D scan of each frame
        double match_distance =
            0.25;  ///< [m] a scan point this close to a map obstacle agrees with the map
        double min_match = 0.5;  ///< frames with fewer agreeing points are not localized
        double diverged_fraction =
            0.5;                   ///< more frames than this not localized: MCL diverged
        TKrrOptions krr;           ///< kernel_bandwidth, kernel_lambda, kernel_cutoff
        double sample_bin = 0.25;  ///< [m] passes and obstacle events are pooled in
                                   ///< bins this size before regression
        double zone_threshold = 0.04;  ///< level above which a cell is in a zone
        double v_max = 0.8;            ///< [m/s] speed outside the zones (eq. 13)
        double v_safe = 0.2;           ///< [m/s] speed inside the zones (eq. 13)
        uint64_t seed = 1;  ///< particle filter seed (with the rawlog's name and size)

        TOptions() {
            section = map.section = obstacles.section = krr.section = "AfraidLearn";
            obstacles.unknown_is_obstacle = obstacles.outside_is_obstacle = false;
        }

      protected:
        void declare(Visitor& v) override;
        /** v_safe <= v_max, the afraid_name form, at least one rawlog or one
         * afraid_in file, no input file twice, every named input file exists,
         * one ground truth per rawlog. */
        void validateRules() const override;
    };

    TOptions options;              ///< [AfraidLearn]
    CAfraidDetector detector;      ///< [AfraidDetector], [Robot]
    localization::CRawlogMcl mcl;  ///< [Localization], [PF_options], [KLD_options]

    /** Reads every section (each options struct loads its own keys, then
     * validate()), adds the command line's rawlogs, applies the --seed
     * override, rejects unknown sections and keys, then prepare(). Any
     * problem: CBadInputError naming the file. */
    void loadFromConfigFile(const common::CIniConfig& c,
                            const std::vector<std::string>& extraRawlogs,
                            std::optional<uint64_t> seedOverride);
    /** Writes every key of every section (config_effective.ini). */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** Every options struct's validate(). Throws CConfigKeyError. */
    void validate() const;
    /** validate(), then loads the map, its distance field, the earlier .afraid
     * files (added up) and the ground truth. Run again after changing options. Throws
     * CConfigKeyError or CBadInputError (a file that cannot be used). */
    void prepare();

    /** Replays every rawlog (none in a merge-only run). A corrupt rawlog stops
     * the replay: partial() becomes true and error() says where; what was
     * learned so far stays. */
    void run(bool quiet);
    /** Adds the earlier grids (if any) to this run's, regresses and finds zones.
     * The merged counts do not depend on the order of rawlogs or afraid_in
     * files, so N per-rawlog runs merged equal one run over the N rawlogs. */
    void generalize();

    const mrpt::maps::COccupancyGridMap2D& map() const { return m_map; }
    const mapping::CDistanceField& distanceField() const { return m_field; }
    const CAfraidGrid& grid() const { return m_grid; }
    const CAfraidGrid& newExperience() const { return m_new; }
    const std::vector<TAfraidEvent>& events() const { return m_events; }
    const std::vector<float>& level() const { return m_level; }
    const std::vector<TAfraidZone>& zones() const { return m_zones; }
    const std::vector<mrpt::math::TPoint2D>& trajectory() const { return m_traj; }
    /** Every frame's estimate (all rawlogs, in order). */
    const std::vector<TTrajectoryPoint>& estimates() const { return m_est; }
    bool partial() const { return !m_error.empty(); }
    /** The rawlogs replayed (after a corrupt one, the rest are not). */
    const std::vector<std::string>& processedRawlogs() const { return m_processed; }
    const std::string& error() const { return m_error; }
    size_t frames() const { return m_frames; }
    size_t localizedFrames() const { return m_localized; }
    bool diverged() const;
    /** MCL position error vs ground truth (NaN without ground truth). */
    double mclErrorMean() const { return m_errN ? m_errSum / m_errN : std::nan(""); }
    double mclErrorMax() const { return m_errN ? m_errMax : std::nan(""); }
    size_t mclErrorSamples() const { return m_errN; }
    /** Mean scan-to-map agreement (NaN without frames, e.g. a merge-only run). */
    double meanMatch() const { return m_frames ? m_matchSum / m_frames : std::nan(""); }
    double replaySeconds() const { return m_replaySeconds; }
    /** The learned level at a world point (0 off the map). */
    double levelAt(double x, double y) const;

  private:
    void replay(const std::string& path, const std::vector<TGroundTruthPose>* gt,
                bool quiet);
    /** Fraction of the scan's points within match_distance of a map obstacle
     * (by the obstacle rule) at the estimated pose. */
    double scanMapAgreement(const mrpt::obs::CObservation2DRangeScan& scan,
                            const mrpt::math::TPose2D& pose) const;
    mrpt::maps::COccupancyGridMap2D m_map;
    mapping::CDistanceField m_field;
    CAfraidGrid m_grid, m_new, m_old;
    std::vector<TAfraidEvent> m_events;
    std::vector<float> m_level;
    std::vector<TAfraidZone> m_zones;
    std::vector<mrpt::math::TPoint2D> m_traj;
    std::vector<TTrajectoryPoint> m_est;
    std::vector<std::vector<TGroundTruthPose>> m_gt;  // per rawlog
    std::vector<std::string> m_processed;
    std::string m_error;
    size_t m_frames = 0, m_localized = 0, m_errN = 0;
    double m_errSum = 0, m_errMax = 0, m_matchSum = 0, m_replaySeconds = 0;
    bool m_sawScan = false;
};

}  // namespace risknav::afraid
