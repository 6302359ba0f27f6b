#pragma once
#include <risknav/afraid/CAfraidGrid.h>
#include <risknav/afraid/kernel_regression.h>
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/common/CSpeedLimiter.h>

#include <string>
#include <vector>

namespace risknav::nav {
/** The afraid map as a speed limiter (Choi, Chung, Song (002) eqs. 13-14, M3):
 * a `.afraid` file written by risknav-afraid-learn, its level generalized by
 * the same kernel ridge regression (afraid::afraidLevel()), and
 * afraid::afraidSpeedLimit() along the robot's path ahead: v_safe when the
 * level exceeds the threshold anywhere within the stopping distance at
 * v_max, v_max otherwise. The path ahead is the controller's predicted
 * path (TSpeedLimitInput::path: MRPT's chosen PTG trajectory), or the
 * straight line along the heading when none is given.
 * Section [CAfraidSpeedLimiter]. */
class CAfraidSpeedLimiter : public common::CSpeedLimiter {
    DEFINE_MRPT_OBJECT(CAfraidSpeedLimiter, risknav::nav)
  public:
    struct TOptions : public common::CDeclaredOptions {
        TOptions() { section = krr.section = "CAfraidSpeedLimiter"; }
        std::string afraid_file;       ///< required: the learned .afraid grid
        double v_max = 0.8;            ///< [m/s] outside zones (002: 0.8)
        double v_safe = 0.2;           ///< [m/s] in zones (002: 0.2)
        double zone_threshold = 0.04;  ///< level above which a cell is afraid
        double sample_bin = 0.25;      ///< [m] as risknav-afraid-learn's
        afraid::TKrrOptions krr;       ///< kernel_bandwidth etc., as the learner's

      protected:
        void declare(Visitor& v) override;
        /** afraid_file required, v_safe <= v_max. */
        void validateRules() const override;
    } options;

    /** Loads options, the grid and its level (throws CBadInputError). */
    void loadConfig(const mrpt::config::CConfigFileBase& c,
                    const std::string& section) override;
    void saveConfig(mrpt::config::CConfigFileBase& c,
                    const std::string& section) const override;
    /** A grid given directly (tests); its level is computed. */
    void setGrid(const afraid::CAfraidGrid& g);
    /** The generalized level at (x, y); 0 off the grid. */
    double levelAt(double x, double y) const;
    const afraid::CAfraidGrid& grid() const { return m_grid; }

  protected:
    common::TSpeedLimit impl_limit(const common::TSpeedLimitInput& in) const override;

  private:
    afraid::CAfraidGrid m_grid;
    std::vector<float> m_level;
};

}  // namespace risknav::nav
