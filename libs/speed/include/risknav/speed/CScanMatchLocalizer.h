#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

namespace risknav::speed {
/** [ScanMatching] of risknav-explore (Explore.ego_motion = scan_matching):
 * the robot's localization, beyond the paper (Miura et al. 2006 take the
 * ego-motion as given). Every key, its range and its doc are declared once,
 * in declare() (CScanMatchLocalizer.cpp). */
struct TScanMatchOptions : public common::CDeclaredOptions {
    TScanMatchOptions() { section = "ScanMatching"; }
    int max_iterations = 40;
    double match_distance = 0.5;       ///< [m] halves on convergence down to the next
    double min_match_distance = 0.05;  ///< [m]
    double min_goodness = 0.3;
    double max_correction = 0.3;      ///< [m]
    double max_correction_deg = 5;    ///< [deg]
    double keyframe_distance = 0.2;   ///< [m]
    double keyframe_angle_deg = 10;   ///< [deg]
    double map_point_spacing = 0.05;  ///< [m]
    /** The odometry prediction's uncertainty since the last scan, the
     * match's prior: sigma_xy = odometry_sigma_xy + odometry_relative * d,
     * sigma_phi = odometry_sigma_deg + odometry_relative * (|dphi| + d / 1 m) (d, dphi:
     * the odometry's motion since the last scan). It holds the directions
     * a scan does not fix (along a corridor). */
    double odometry_sigma_xy = 0.01;  ///< [m]
    double odometry_sigma_deg = 0.5;  ///< [deg]
    double odometry_relative = 0.05;  ///< [m/m and rad/rad]
    double point_sigma = 0.05;        ///< [m]
    /** Estimate the laser's constant range offset with the matches and take
     * it off the scans and the map. A range offset pushes every wall away
     * along the beams, by its cosine to the wall's normal: a wall seen
     * square from one place and obliquely from another does not lie where
     * it was, and the match turns the robot to fit it; each keyframe adds
     * that turn to the map, so the belief drifts (a simulated laser's rays
     * end inside the cell they hit: half a cell further on average). */
    bool estimate_range_bias = true;
    double range_bias_sigma = 0.05;  ///< [m]
    double range_bias_rate = 0.1;
    double max_range_bias = 0.2;  ///< [m]

  protected:
    void declare(Visitor& v) override;
    void validateRules() const override;
};

/** A light SLAM front end for the explorer (beyond the paper: the robot's
 * localization, not its speed rule, which Miura et al. 2006 leave to the
 * ego-motion estimate): each laser scan is aligned to the point map the
 * robot has built from its earlier scans (an ICP: Gauss-Newton on the
 * point-to-line distances of the scan's points to the lines through their
 * nearest map points, found in the map's MRPT k-d tree (CSimplePointsMap), a
 * Cauchy kernel, and the odometry's prediction as a prior whose spread
 * grows with the motion since the last scan: it holds what the scan does
 * not fix, e.g. the position along a corridor). Only map points on a line
 * are matched: the end of a wall's seen part, point to point, would pull a
 * scan that sees the wall go on back to it. The aligned pose is the belief;
 * the scan's new points (one per map_point_spacing cell, the first one kept)
 * are added to the map at it every keyframe_distance / keyframe_angle_deg.
 * A match with too few correspondences or too large a correction is
 * refused: the belief then moves by odometry alone. There is no loop
 * closure: the belief drifts only where the robot sees nothing it has seen
 * before, and comes back to its map where it does.
 *
 * All poses in the odometry's frame at the start (the "ego frame"): the
 * belief starts at the first odometry pose. */
class CScanMatchLocalizer {
  public:
    /** Throws CConfigKeyError for bad options. */
    explicit CScanMatchLocalizer(const TScanMatchOptions& o = {});

    /** One scan at the odometry pose `odometry`: predict by the odometry
     * increment, align, maybe add to the map. The first call starts the
     * belief at `odometry` and the map with the scan. A null scan: the
     * prediction only. Returns the belief. */
    mrpt::math::TPose2D update(const mrpt::math::TPose2D& odometry,
                               const mrpt::obs::CObservation2DRangeScan* scan);

    /** The belief at odometry pose `odometry` between scans: the last
     * belief moved by the odometry increment since its scan. */
    mrpt::math::TPose2D predict(const mrpt::math::TPose2D& odometry) const;

    const mrpt::math::TPose2D& pose() const { return m_pose; }
    const mrpt::maps::CSimplePointsMap& map() const { return m_map; }
    const TScanMatchOptions& options() const { return m_o; }

    struct TStats {
        size_t scans = 0;      ///< update() calls with a scan
        size_t accepted = 0;   ///< of them, matches taken as the belief
        size_t refused = 0;    ///< matches refused (goodness or correction)
        size_t keyframes = 0;  ///< scans added to the map
        double lastGoodness = 0;
        double lastCorrection = 0;  ///< [m] of the last accepted match
    };
    const TStats& stats() const { return m_stats; }

    /** The alignment of robot-frame points to the map from `prior` (no
     * refusal: what update() would weigh). */
    struct TAlignment {
        mrpt::math::TPose2D pose;
        double goodness = 0;  ///< share of the points with a map point near
        int iterations = 0;
        /** [m] the change of the range offset that fits best (with beam
         * directions only) */
        double rangeBiasChange = 0;
    };
    TAlignment align(const std::vector<mrpt::math::TPoint2D>& robotFramePoints,
                     const mrpt::math::TPose2D& prior, double priorSigmaXY,
                     double priorSigmaPhi) const;

    /** [m] the laser's range offset as estimated so far (0 without
     * estimate_range_bias): the scans' and the map's ranges less it. */
    double rangeBias() const { return m_rangeBias; }

  private:
    /** The alignment; with the beams' directions (robot frame, one per
     * point) the range offset's change is estimated too. */
    TAlignment alignImpl(const std::vector<mrpt::math::TPoint2D>& robotFramePoints,
                         const std::vector<mrpt::math::TPoint2D>* beamDirections,
                         const mrpt::math::TPose2D& prior, double priorSigmaXY,
                         double priorSigmaPhi) const;
    void addToMap(const std::vector<mrpt::math::TPoint2D>& robotFramePoints,
                  const std::vector<mrpt::math::TPoint2D>& beamDirections,
                  const mrpt::math::TPose2D& at);
    /** Every map point at its raw position less the current range offset
     * along its beam. */
    void applyRangeBiasToMap();
    struct TNormal {
        bool known = false, line = false;
        double nx = 0, ny = 0;
    };
    const TNormal& normalOf(size_t mapPoint) const;

    TScanMatchOptions m_o;
    bool m_started = false;
    mrpt::math::TPose2D m_pose, m_pose0, m_odometry, m_keyframe;
    mrpt::maps::CSimplePointsMap m_map;
    std::unordered_set<uint64_t> m_cells;
    /** per map point: where its beam ended (the raw range) and the beam's
     * unit direction, world frame */
    std::vector<mrpt::math::TPoint2D> m_raw, m_beam;
    double m_rangeBias = 0, m_mapRangeBias = 0;  ///< now, and the map's
    mutable std::vector<TNormal> m_normals;      ///< per map point, when first asked
    TStats m_stats;
};
}  // namespace risknav::speed
