#pragma once
#include <risknav/common/CDeclaredOptions.h>

#include <string>

namespace risknav::mapping {
/** The forward sensor model of one range sensor for the local probabilistic
 * grid (Miura et al. 2006 (000) section 2, PAPER_NOTES M1 "Mapping"):
 * observation likelihoods P(O|E), P(O|~E) and the range uncertainty
 * [R_min, R_max] = [R - delta(R), R + delta(R)] with
 * delta(R) = range_uncertainty + range_uncertainty_quad * R^2 (constant for a
 * laser, growing with R^2 for stereo). Section per sensor ([MapLaser],
 * [MapRange2] in risknav-explore). */
struct TSensorModel : public common::CDeclaredOptions {
    TSensorModel() { section = "MapLaser"; }
    // Defaults: a noisy stereo-like sensor; they give N = 5 (the paper's N).
    double p_obs_given_obstacle =
        0.6;                          ///< P(O|E): a cell with an obstacle reads occupied
    double p_obs_given_free = 0.45;   ///< P(O|~E): a free cell reads occupied
    double range_uncertainty = 0.05;  ///< [m] delta at R = 0
    double range_uncertainty_quad = 0;  ///< [1/m] delta grows by this * R^2

    /** delta(R) [m]. */
    double delta(double range) const {
        return range_uncertainty + range_uncertainty_quad * range * range;
    }

  protected:
    /** Likelihoods in (0, 1), uncertainties >= 0. */
    void declare(Visitor& v) override;
    /** P(O|E) > P(O|~E): an occupied reading is evidence of an obstacle. */
    void validateRules() const override;
};

/** Bayes update of one cell, (000) section 2 (its display equation for
 * P(E|O)) and the O-bar form:
 *  occupied reading: P' = P(O|E) P / (P(O|E) P + P(O|~E) (1 - P));
 *  free reading:     P' = P(~O|E) P / (P(~O|E) P + P(~O|~E) (1 - P)),
 * with P(~O|.) = 1 - P(O|.). */
inline double bayesUpdate(double p, bool occupiedReading, const TSensorModel& m) {
    // inline: it runs once per cell and scan (CLocalProbGrid::integrateScan)
    const double le =
        occupiedReading ? m.p_obs_given_obstacle : 1.0 - m.p_obs_given_obstacle;
    const double lf = occupiedReading ? m.p_obs_given_free : 1.0 - m.p_obs_given_free;
    return le * p / (le * p + lf * (1.0 - p));
}

/** The necessary number of observations N of (000) section 3.2 (typical-case
 * analysis): free readings applied to a cell from P = pStart until P falls
 * below freeThreshold. Throws std::invalid_argument if the model never gets
 * there (P(O|E) <= P(O|~E)) or needs more than 1000. */
int necessaryObservations(const TSensorModel& m, double freeThreshold,
                          double pStart = 0.5);
}  // namespace risknav::mapping
