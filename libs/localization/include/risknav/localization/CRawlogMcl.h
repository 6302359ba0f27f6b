#pragma once
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/slam/CMonteCarloLocalization2D.h>
#include <risknav/common/CValidatedOptions.h>

#include <memory>
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
    struct TOptions : public common::CValidatedOptions {
        int particles = 5000;          ///< initial particles
        std::string init = "pose";     ///< pose | global
        mrpt::math::TPose2D initPose;  ///< init = pose: centre of a uniform box
        double init_xy = 1.0;  ///< [m] half-width of the box in x (init_xy = "hx [hy]")
        double init_y = 1.0;   ///< [m] half-width of the box in y
        double init_phi_deg = 180;           ///< [deg] half-width of the heading range
        double lf_std_hit = 0.2;             ///< [m] likelihood field sigma
        int lf_decimation = 5;               ///< use every N-th ray
        double lf_max_corrs_distance = 0.3;  ///< [m]
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                              const std::string& s) const override;
        void validate() const override;
    } options;
    mrpt::bayes::CParticleFilter::TParticleFilterOptions pfOptions;
    mrpt::slam::TKLDParams kldOptions;

    CRawlogMcl();
    /** Loads options, [PF_options] and [KLD_options]. */
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

  private:
    mrpt::maps::COccupancyGridMap2D::Ptr m_map;
    mrpt::bayes::CParticleFilter m_pf;
    mrpt::slam::CMonteCarloLocalization2D m_pdf;
};

}  // namespace risknav::localization
