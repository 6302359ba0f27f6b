#pragma once
#include <risknav/common/CAppRunner.h>
#include <risknav/common/CDeclaredOptions.h>

#include <cstdint>
#include <string>
#include <vector>

namespace risknav::nav {
/** [AfraidExperiment]: the closed-loop experiment of Choi, Chung, Song (002)
 * section 3 (keys in config/risknav-navigate.ini). Per seed: learning laps at
 * v_safe through MRPT's engine, recording a rawlog; the afraid map learned
 * from it (risknav-afraid-learn's CAfraidLearner: MCL on the map, the afraid
 * detector, kernel regression); then test laps at v_max with the learned
 * CAfraidSpeedLimiter and without it (same seed: the same people). */
struct TAfraidExperimentOptions : public common::CDeclaredOptions {
    TAfraidExperimentOptions() { section = "AfraidExperiment"; }
    std::vector<uint64_t> seeds{1, 2, 3, 4, 5};  ///< whole, distinct
    int learning_laps = 3;       ///< laps of the route at v_safe (mode back_and_forth)
    int test_laps = 1;           ///< laps at v_max, with and without the limiter
    double v_safe = 0.2;         ///< [m/s] the learning speed (002: 0.2)
    double v_max = 0.8;          ///< [m/s] the fast speed (002: 0.8)
    double section_length = 10;  ///< [m] the compared door section (002: 10 m)
    double lead_in = 1;  ///< [m] the section starts this far before the first zone

  protected:
    void declare(Visitor& v) override;
    /** 1 to 100 distinct seeds, v_safe <= v_max. */
    void validateRules() const override;
};

/** Runs the experiment of a config with [AfraidExperiment] (risknav-navigate):
 * experiment.csv / experiment.md (per seed and mean [min, max]),
 * experiment_speed.png, the first seed's learned .afraid, navlog, rawlog and
 * pictures, summary.json. */
void runAfraidExperiment(const common::TAppContext& ctx);

}  // namespace risknav::nav
