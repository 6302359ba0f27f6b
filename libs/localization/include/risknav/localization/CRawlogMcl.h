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
