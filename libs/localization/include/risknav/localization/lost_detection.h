#pragma once
#include <risknav/common/CDeclaredOptions.h>
#include <risknav/localization/scan_fit.h>

#include <string>

namespace risknav::localization {
/** When Monte Carlo localization counts as lost, and how CRawlogMcl::recover()
 * re-spreads its particles (section name chosen by the host app; keys in
 * snake_case, as every risknav option). The scan-fit test is the afraid
 * learner's "localized" test (match_distance 0.25 m, min_match 0.5), not
 * tuned to one log. Measured with it: a localized filter's fit is 0.93-1.0
 * on MRPT's localization_demo log and, on simulated rawlogs with people and
 * unmapped boxes (the afraid validation worlds, 3 and 10 laps, seed 1;
 * every range) its 1st percentile is 0.56-0.84; three checks in a row below
 * 0.5 happened 0 times in three of the four worlds and 2 (3 laps) / 5 (10
 * laps) times in the T junction, where the filter was 0.26-0.28 m off. A raised min_fit
 * alarms more on people (0.7: 0-23 times a world). Filters 3 m off on the
 * demo log: across its corridor lost at the 3rd frame (fit 0.22-0.32);
 * along it not before the 16th (fit 0.52-0.79 at first): a shift along a
 * featureless corridor keeps most scan points on its walls, which no
 * scan-fit threshold can see until the corridor's ends or doors come into
 * view. */
struct TLostDetectionOptions : public common::CDeclaredOptions {
    /** risknav-navigate's section; a host loads it from the one it chooses. */
    TLostDetectionOptions() { section = "LostLocalization"; }

    /** [m] a scan point within this of a map obstacle (and not deeper than
     * this inside one) fits the map (scanMapFit()). */
    double fit_distance = 0.25;
    /** Fraction of the scan's points that must fit at the filter's mean
     * pose; fewer: the scan does not fit (the filter is off). */
    double min_fit = 0.5;
    /** [m] returns farther than this from the sensor are not counted: at
     * long range a small heading error moves a point off the wall (1 deg at
     * 30 m: 0.5 m); 0 = every range. */
    double max_range = 20.0;
    /** Fewer points than this (within max_range) and the fit is not judged:
     * an open space, or a sensor that sees nothing, is no evidence. */
    int min_points = 20;
    /** [m] the particles' position spread sqrt(var x + var y) above which
     * the filter has no single estimate (it is spread over the map, or
     * split between places). */
    double max_spread_xy = 1.0;
    /** [deg] the same for the heading's standard deviation. */
    double max_spread_phi_deg = 30.0;
    /** A filter is lost after this many consecutive checks that failed
     * (a person in front of the laser fails one check, not three). */
    int lost_after = 3;
    /** Checks a filter may take to converge after CRawlogMcl::initialize()
     * or recover(): until its spread is first within max_spread_xy and
     * max_spread_phi_deg no check fails (a spread-out filter is localizing,
     * not lost, and its mean is no pose to fit a scan at); if it has not
     * converged after this many checks it is lost ("not_converged"). Without
     * this grace a recovery that re-spreads the particles over a +-2 m box
     * (spread ~1.6 m) was judged lost again lost_after checks later, and
     * re-spread again, before its scans could pick the robot out: a loop
     * that never converged on the Malaga campus map. 25 checks are 5 s at
     * risknav-navigate's 0.2 s cycle; a filter re-spread over
     * recovery_xy = 2 m converges in 2-6 checks when its scans see walls. */
    int converge_checks = 25;
    /** recover(): half-width [m] of the box around the mean pose over whose
     * free cells the particles are re-spread (the standard MCL recovery; a
     * global recovery spreads them over the whole map's free cells). */
    double recovery_xy = 2.0;
    double recovery_phi_deg = 180.0;  ///< recover(): heading half-range [deg]
    /** recover(): particles drawn. The box (recovery_xy, any heading) is 4x
     * the default initial box (+-1 m, any heading; 5000 particles): the
     * same density, 0.35 particles per KLD bin, the bound CRawlogMcl
     * documents (kMinParticlesPerBin = 0.1) with the initial set's margin.
     * 5000 (0.09 per bin) was below even that bound. */
    int recovery_particles = 20000;

  protected:
    void declare(Visitor& v) override;
};

/** One check of a particle filter's state against the last scan. */
struct TLocalizationCheck {
    /** This check failed: the scan does not fit at the mean pose, or the
     * particles are spread (reason says which). */
    bool failed = false;
    /** failed for TLostDetectionOptions::lost_after consecutive checks
     * (CRawlogMcl::checkLost() counts them; judgeLocalization() alone:
     * lost == failed). */
    bool lost = false;
    /** "" | "scan_fit" | "spread_xy" | "spread_phi" (the first that failed,
     * in this order) | "not_converged" (CRawlogMcl::checkLost(): spread for
     * TLostDetectionOptions::converge_checks checks since the last reset). */
    std::string reason;
    /** CRawlogMcl::checkLost(): the filter has not converged since its last
     * initialize() or recover() and is within converge_checks of it: this
     * check does not count (failed is false, reason says what it saw). */
    bool converging = false;
    TScanFit fit;               ///< the scan at the mean pose
    double fitFraction = 0;     ///< fit.fraction(); NaN without points
    bool fitJudged = false;     ///< fit.points >= min_points
    double spreadXY = 0;        ///< [m] sqrt(var x + var y) of the particles
    double spreadPhiDeg = 0;    ///< [deg] the heading's standard deviation
    double ess = 0;             ///< normalized ESS in [0, 1] (reported only)
    size_t particles = 0;       ///< reported only
    int consecutiveFailed = 0;  ///< failed checks in a row, this one included
};

/** The per-check rule, a pure function: failed when the fit is judged (at
 * least min_points points) and below min_fit, or spreadXY > max_spread_xy, or
 * spreadPhiDeg > max_spread_phi_deg. Sets failed, reason, fitFraction,
 * fitJudged and lost = failed; the caller's figures (spread, ess, particles)
 * are copied in. ESS is not used: right after resampling the weights are
 * equal (ESS = 1) whatever the filter's state. */
TLocalizationCheck judgeLocalization(const TScanFit& fit, double spreadXY,
                                     double spreadPhiDeg, const TLostDetectionOptions& o);
}  // namespace risknav::localization
