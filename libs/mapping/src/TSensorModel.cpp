#include <risknav/common/config_read.h>
#include <risknav/mapping/TSensorModel.h>

#include <stdexcept>

using namespace risknav::common;

namespace risknav::mapping {
void TSensorModel::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                      const std::string& s) {
    section = s;
    p_obs_given_obstacle = readDouble(c, s, "p_obs_given_obstacle", p_obs_given_obstacle);
    p_obs_given_free = readDouble(c, s, "p_obs_given_free", p_obs_given_free);
    range_uncertainty = readDouble(c, s, "range_uncertainty", range_uncertainty);
    range_uncertainty_quad =
        readDouble(c, s, "range_uncertainty_quad", range_uncertainty_quad);
}

void TSensorModel::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                    const std::string& s) const {
    writeKey(c, s, "p_obs_given_obstacle", p_obs_given_obstacle);
    writeKey(c, s, "p_obs_given_free", p_obs_given_free);
    writeKey(c, s, "range_uncertainty", range_uncertainty);
    writeKey(c, s, "range_uncertainty_quad", range_uncertainty_quad);
}

void TSensorModel::validate() const {
    checkKey(section, "p_obs_given_obstacle", p_obs_given_obstacle,
             TRange{0, 1, true, true, ""});
    checkKey(section, "p_obs_given_free", p_obs_given_free, TRange{0, 1, true, true, ""});
    checkRule(p_obs_given_obstacle > p_obs_given_free, section, "p_obs_given_obstacle",
              numberText(p_obs_given_obstacle),
              "must be > p_obs_given_free (an occupied reading must be evidence of an "
              "obstacle)");
    checkKey(section, "range_uncertainty", range_uncertainty, TRange::closed(0, 5, "m"));
    checkKey(section, "range_uncertainty_quad", range_uncertainty_quad,
             TRange::closed(0, 1, "1/m"));
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
