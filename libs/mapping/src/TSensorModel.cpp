#include <risknav/common/config_read.h>
#include <risknav/mapping/TSensorModel.h>

#include <stdexcept>

using namespace risknav::common;

namespace risknav::mapping {
void TSensorModel::declare(Visitor& v) {
    v.number(p_obs_given_obstacle, "p_obs_given_obstacle", TRange{0, 1, true, true, ""},
             "P(O|E): a cell with an obstacle reads occupied (> p_obs_given_free)");
    v.number(p_obs_given_free, "p_obs_given_free", TRange{0, 1, true, true, ""},
             "P(O|~E): a free cell reads occupied");
    v.number(range_uncertainty, "range_uncertainty", TRange::closed(0, 5, "m"),
             "range uncertainty delta at R = 0");
    v.number(range_uncertainty_quad, "range_uncertainty_quad",
             TRange::closed(0, 1, "1/m"), "delta grows by this * R^2");
}

void TSensorModel::validateRules() const {
    checkRule(p_obs_given_obstacle > p_obs_given_free, section, "p_obs_given_obstacle",
              numberText(p_obs_given_obstacle),
              "must be > p_obs_given_free (an occupied reading must be evidence of an "
              "obstacle)");
}

int necessaryObservations(const TSensorModel& m, double freeThreshold, double pStart) {
    if (!(m.p_obs_given_obstacle > m.p_obs_given_free))
        throw std::invalid_argument("a free reading never lowers P(E) with this model");
    double p = pStart;
    for (int n = 1; n <= 1000; n++) {
        p = bayesUpdate(p, false, m);
        if (p < freeThreshold)
            return n;
    }
    throw std::invalid_argument("more than 1000 observations to decide a free cell");
}
}  // namespace risknav::mapping
