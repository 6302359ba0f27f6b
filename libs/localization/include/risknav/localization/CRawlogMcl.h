#pragma once
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/slam/CMonteCarloLocalization2D.h>
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/localization/lost_detection.h>
#include <risknav/mapping/CDistanceField.h>
#include <risknav/mapping/TObstacleRule.h>

#include <memory>
#include <optional>
#include <string>

namespace risknav::localization {
/** Pose estimate after one filter step. */
struct TMclEstimate {
    mrpt::math::TPose2D mean;
    mrpt::math::CMatrixDouble33 cov;
    size_t particles = 0;
    double ess = 0;
};

/** Monte Carlo localization over a rawlog with MRPT's
 * CMonteCarloLocalization2D and CParticleFilter: KLD-adaptive sample size,
 * likelihood-field observation model on an occupancy grid. Section
 * [Localization] of the app config; the particle-filter and KLD settings use
 * MRPT's own keys in [PF_options] and [KLD_options] (the same sections
 * pf-localization reads, so one config can drive both). */
class CRawlogMcl {
  public:
    /** [Localization], risknav's keys. MRPT's [PF_options] and [KLD_options]
     * stay read by CRawlogMcl::loadFromConfigFile() (MRPT's structs). */
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = "Localization"; }
        int particles = 5000;          ///< initial particles
        std::string init = "pose";     ///< pose | global
        mrpt::math::TPose2D initPose;  ///< init = pose: centre of a uniform box
        double init_xy = 1.0;  ///< [m] half-width of the box in x (init_xy = "hx [hy]")
        double init_y = 1.0;   ///< [m] half-width of the box in y
        double init_phi_deg = 180;           ///< [deg] half-width of the heading range
        double lf_std_hit = 0.2;             ///< [m] likelihood field sigma
        int lf_decimation = 5;               ///< use every N-th ray
        double lf_max_corrs_distance = 0.3;  ///< [m]

      protected:
        void declare(Visitor& v) override;
    } options;
    mrpt::bayes::CParticleFilter::TParticleFilterOptions pfOptions;
    mrpt::slam::TKLDParams kldOptions;
    /** When the filter counts as lost, and how recover() re-spreads it. Not
     * read by loadFromConfigFile(): the host app loads it from the section
     * it chooses (loadOptions(mcl.lostOptions, c, "...")). */
    TLostDetectionOptions lostOptions;
    /** Which map cells the range sensor echoes from: the observation model's
     * obstacles. With a rule, initialize() gives MRPT's likelihood field (and
     * the lost check's scan fit) exactly the cells the rule calls obstacles
     * (a ring around the map with outside_is_obstacle) and no others;
     * without one (nullopt) the grid is taken as it is (MRPT's likelihood
     * field: P(free) < 0.5; the scan fit: occupancy >= 0.65).
     * loadFromConfigFile() reads it from [World] when the config has that
     * section: the map's rule by which risknav's simulated sensors echo
     * (CSimWorld), so that the filter expects a return where the laser gets
     * one. On SLAM maps with many grey cells (the Malaga campus grid: ~7x as
     * many cells of P(free) 0.4-0.6 as occupied ones) the world's laser
     * echoes on unknown cells that MRPT's field did not count: at the true
     * pose only 22-50 % of the scan fit, the filter was judged lost while
     * 0.00 m off, and its recoveries lost it. */
    std::optional<mapping::TObstacleRule> obstacleRule;

    CRawlogMcl();
    /** Loads options, [PF_options], [KLD_options] and (when the config has
     * the section) obstacleRule from [World]. */
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c);
    /** Writes [Localization], [PF_options] and [KLD_options] back. */
    void saveToConfigFile(mrpt::config::CConfigFileBase& c) const;
    /** Particles per KLD bin (KLD_binSize_XY^2 x KLD_binSize_PHI) of the
     * initial region that the start set needs at least. The first steps only
     * copy and shift the start poses, so with too few none is near the robot:
     * the filter is lost, spreads over many bins and KLD draws
     * KLD_maxSampleSize particles every frame. Measured on the corridor's
     * 15129-bin box (seed 1): 10 to 3000 start particles (up to 0.2 per bin)
     * were lost and took ~25x longer, 4000 and 5000 localized; MRPT's
     * localization_demo (40000 in 259002 bins, 0.15 per bin) localizes. A
     * necessary bound, below MRPT's own demo, not a sufficient one: how many
     * a map needs also depends on its symmetry. */
    static constexpr double kMinParticlesPerBin = 0.1;
    /** KLD bins of the initial region: the free cells (P(free) >= 0.7, as
     * resetUniformFreeSpace() draws them) of the whole map (init = global) or
     * of the init box, times the heading range; at least one bin per axis. */
    double initialBins(const mrpt::maps::COccupancyGridMap2D& grid) const;
    /** The fewest `particles` that cover the initial region on this map:
     * kMinParticlesPerBin x initialBins(), at least 10. */
    int minParticles(const mrpt::maps::COccupancyGridMap2D& grid) const;
    /** Throws CConfigKeyError ([Localization] particles) when options.particles
     * is below minParticles(grid). Call once the map is known, before
     * initialize(). */
    void checkParticles(const mrpt::maps::COccupancyGridMap2D& grid) const;
    /** Sets the map and draws the initial particles (seeded). */
    void initialize(const mrpt::maps::COccupancyGridMap2D& grid, uint64_t seed);
    /** One prediction + update step. */
    TMclEstimate step(const mrpt::obs::CActionCollection& actions,
                      const mrpt::obs::CSensoryFrame& sf);
    /** The particles' mean pose, covariance, count and ESS now. */
    TMclEstimate estimate() const;
    /** The map the observation model uses (after initialize(): the grid
     * under obstacleRule; nullptr before). */
    mrpt::maps::COccupancyGridMap2D::Ptr map() const { return m_map; }
    /** The particles (after initialize()). */
    const mrpt::slam::CMonteCarloLocalization2D& particles() const { return m_pdf; }

    /** Is the filter lost? Call once per step(), with the same frame: its
     * first 2D range scan (or the first labelled `scanLabel`) is fitted to
     * the map at the particles' mean pose (scanMapFit(), lostOptions'
     * fit_distance and max_range), the particles' spread is taken
     * (sqrt(var x + var y), the heading's standard deviation), and
     * judgeLocalization() says whether this check failed; `lost` once
     * lostOptions.lost_after checks in a row have failed (a passed check
     * starts the count again). A frame without a scan judges the spread
     * only. After initialize() or recover() the count starts at 0 and the
     * filter is converging: its checks do not fail (`converging`) until its
     * spread is first within the bounds, and it is lost ("not_converged")
     * if that has not happened within lostOptions.converge_checks checks. */
    TLocalizationCheck checkLost(const mrpt::obs::CSensoryFrame& sf,
                                 const std::string& scanLabel = "");
    /** The same figures for one scan (nullptr: none), without counting. */
    TLocalizationCheck checkLocalization(
        const mrpt::obs::CObservation2DRangeScan* scan) const;
    /** The standard MCL recovery: draws lostOptions.recovery_particles
     * particles anew over the free cells (P(free) >= 0.7, as initialize())
     * of a box of +-recovery_xy around the mean pose with headings within
     * +-recovery_phi_deg of its heading, or (global, or no free cell in the
     * box) of the whole map with any heading. The next steps' scans then
     * pick the robot's pose out of them. Resets the lost count; the filter
     * is converging again (checkLost()). */
    void recover(bool global = false);

  private:
    /** The map's obstacles for scanMapFit() (built at the first check). */
    const mapping::CDistanceField& fitField() const;
    mrpt::maps::COccupancyGridMap2D::Ptr m_map;
    mrpt::bayes::CParticleFilter m_pf;
    mrpt::slam::CMonteCarloLocalization2D m_pdf;
    mutable std::shared_ptr<const mapping::CDistanceField> m_fitField;
    int m_failedChecks = 0;
    bool m_converged = false;    ///< spread within bounds since the last reset
    int m_checksSinceReset = 0;  ///< checkLost() calls since the last reset
};

}  // namespace risknav::localization
