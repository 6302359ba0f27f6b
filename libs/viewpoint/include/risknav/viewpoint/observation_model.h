#pragma once
#include <risknav/geometry/CSegmentIndex.h>
#include <risknav/viewpoint/TPolygonWorld.h>

#include <mrpt/math/TPose2D.h>

#include <array>
#include <functional>
#include <optional>
#include <vector>

/** The three landmark-observation strategies of Yamashita et al. (004 section
 * III, 003 sections 3-4): camera model, pose estimation from the image
 * measurements, and the worst-case error over every sign combination of the
 * image errors. Pure functions on small structs.
 *
 * Conventions. The robot pose is (x, y, phi); its two cameras sit at
 * +-b_r on its left axis (left camera at +b_r), optical axes parallel to the
 * floor at the landmarks' height, each panned by its own angle relative to
 * the robot's heading. Image u [px] grows to the right of the optical axis,
 * v upwards; a point at depth t and lateral offset s (to the right) images
 * at u = f s / t. Landmarks are circles of radius r on walls, facing a known
 * direction (003 section 2.2). */
namespace risknav::viewpoint {
struct TCameraRig {
    double b_r = 0.1;     ///< [m] camera offset from the centre (003: 100 mm)
    double focal = 3000;  ///< [px] focal length f (003 section 6)
    int width = 640;      ///< [px] image size (003 section 6)
    int height = 480;     ///< [px]
    double maxRange = 5;  ///< [m] landmark distance limit
    double maxIncidence = 75 * M_PI / 180;  ///< [rad] off the landmark's facing
    double panLimit = M_PI;                 ///< [rad] |pan| limit of each camera
};

/** The image errors: +-du, +-dv [px] on a landmark's centre, +-dr [px] on its
 * apparent radius (004 section III-E, Fig. 5). */
struct TImageErrors {
    double du = 1, dv = 1, dr = 1;
};

enum class TStrategy : char { Stereo = 'A', TwoLandmark = 'B', ThreeLandmark = 'C' };

/** One way of observing: strategy, landmarks, which camera sees what, pans.
 * A (stereo): lm[0] seen by both cameras, axes parallel (pan[0] == pan[1]).
 * B (two-landmark): lm[0] = the nearer landmark j, seen by camera `side`
 *   (+1 left, -1 right), whose apparent size gives its distance l_j; lm[1] =
 *   the farther landmark i, seen by the other camera.
 * C (three-landmark): lm[0], lm[1] in the image of camera `side`, lm[2] in
 *   the other camera's image; only the centres are used. */
struct TObservation {
    TStrategy strategy = TStrategy::Stereo;
    std::array<int, 3> lm{{-1, -1, -1}};  ///< indices into the landmark list
    int side = 1;                         ///< see above
    std::array<double, 2> pan{{0, 0}};    ///< [rad] left, right camera (robot frame)
    int landmarkCount() const {
        return strategy == TStrategy::Stereo
                   ? 1
                   : (strategy == TStrategy::TwoLandmark ? 2 : 3);
    }
};

/** The image measurements of an observation, one vector per strategy:
 * A: [u_c,L, w_L, u_c,R, w_R] (centre and half-width of the landmark's
 *    horizontal extent in each image; its ends are u_c +- w);
 * B: [u_j, r_j, u_i] (centre and vertical apparent radius of the near
 *    landmark, centre of the far one);
 * C: [u_0, u_1, u_2] (the three centres). */
using TMeasurement = std::vector<double>;

/** Camera centre in the world: side +1 left, -1 right. */
mrpt::math::TPoint2D cameraCentre(const mrpt::math::TPose2D& robot, int side, double b_r);

/** Exact image of the world point q in a camera at c with world heading psi:
 * (u [px], depth t [m]); t <= 0: behind the camera. */
std::pair<double, double> project(const mrpt::math::TPoint2D& c, double psi,
                                  const mrpt::math::TPoint2D& q, double f);

/** The landmark's horizontal ends (centre +- r along the wall). */
std::pair<mrpt::math::TPoint2D, mrpt::math::TPoint2D> landmarkEnds(const TLandmark& l);

/** Parallel stereo, 003 eqs. (1) and (3) (eq. (2), w, is the height and
 * unused in the plane): s = b (u_l + u_r) / (2 d), t = b f / d with the
 * disparity d = u_l - u_r in our u-to-the-right convention (the paper writes
 * d = u_r - u_l with u to the left); (t, s) in the frame centred between the
 * cameras. Returns nullopt for d <= 0 (no intersection in front). */
std::optional<std::pair<double, double>> parallelStereo(double uL, double uR, double b,
                                                        double f);

/** The measurements the observation would give at the true pose. */
TMeasurement predictMeasurement(const TObservation& o, const mrpt::math::TPose2D& pose,
                                const std::vector<TLandmark>& lms, const TCameraRig& rig);

/** Pose from the measurements (003 sections 3.1-3.3):
 * A: both ends of the landmark triangulated from the two cameras (eqs.
 *    (1)-(3); with panned cameras the baseline is not perpendicular to the
 *    axes, so the rays are intersected exactly, which is eqs. (1)-(3) at pan
 *    0), then the pose that maps the two measured ends onto the map's.
 * B: l_j from the near landmark's apparent size (l = f r / r_image), the
 *    bearing of i from the other camera; l_i follows from l_j, the angle and
 *    d_ij (law of cosines: two roots = the two intersections of the circles
 *    of eqs. (4)-(5)); the root nearest the dead-reckoning `prior` is kept
 *    (the paper's rule).
 * C: the three bearings (eqs. (6)-(7), with each camera's own centre),
 *    solved by damped Newton iteration from the dead-reckoning `prior`.
 * nullopt when the geometry gives no solution (rays parallel, no real
 * root, singular or non-converging Newton system). */
std::optional<mrpt::math::TPose2D> solvePose(const TObservation& o, const TMeasurement& z,
                                             const std::vector<TLandmark>& lms,
                                             const TCameraRig& rig,
                                             const mrpt::math::TPose2D& prior);

/** The image error bound of each measurement component (see TMeasurement):
 * du on centres, dr on sizes. dv moves images vertically only, which the
 * planar pose does not use, so no component carries it. */
std::vector<double> measurementErrors(const TObservation& o, const TImageErrors& e);

/** Worst case over every sign combination of the image errors (004 section
 * III-E): the largest position error E_pos,max [m] and heading error
 * dphi_max [rad] of the pose re-solved from the perturbed measurements.
 * ok = false (degenerate) when the exact measurements do not give back the
 * true pose or some combination has no solution: near-singular geometry
 * (e.g. robot and three landmarks on one circle or line), never NaN. */
struct TWorstCase {
    bool ok = false;
    bool gaveUp = false;  ///< stopped early by giveUp (not degenerate)
    double ePos = 0;      ///< [m]
    double dPhi = 0;      ///< [rad]
};
/** giveUp(ePos, dPhi), when given, is asked after every sign combination
 * with the largest errors so far (lower bounds of the final ones): true
 * stops the evaluation (gaveUp, not ok), e.g. when the observation can no
 * longer beat a better one already found. */
TWorstCase worstCaseError(
    const TObservation& o, const mrpt::math::TPose2D& pose,
    const std::vector<TLandmark>& lms, const TCameraRig& rig, const TImageErrors& e,
    const std::function<bool(double ePos, double dPhi)>& giveUp = {});

/** E_ang,max(m): the position error after moving m with heading error dphi
 * (004 Fig. 6(b)): the chord 2 m sin(dphi / 2). */
inline double angularError(double m, double dPhi) {
    return 2 * m * std::sin(std::min(dPhi, M_PI) / 2);
}
/** 004 eq. (1): E_max(p, m) = E_pos,max(p) + E_ang,max(p, m). */
inline double totalError(const TWorstCase& w, double m) {
    return w.ePos + angularError(m, w.dPhi);
}

/** Which cameras can see each landmark from a pose (004 section III-E): in
 * range, seen from the front (within maxIncidence of its facing), the pan
 * within the limit, the whole landmark fitting the image when centred, the
 * line of sight clear of every obstacle edge (`occluders`). */
struct TLandmarkView {
    std::array<bool, 2> visible{{false, false}};  ///< left, right camera
    std::array<double, 2> pan{{0, 0}};            ///< [rad] pan that centres it
    std::array<double, 2> dist{{0, 0}};           ///< [m] from each camera
    double distCentre = 0;                        ///< [m] from the robot centre
};
std::vector<TLandmarkView> landmarkViews(const mrpt::math::TPose2D& pose,
                                         const std::vector<TLandmark>& lms,
                                         const TCameraRig& rig,
                                         const geometry::CSegmentIndex& occluders);

/** Every observation the views allow: A for each landmark both cameras see
 * with parallel axes and both ends inside both images; B for each pair
 * (nearer one by distance, either camera on it); C for each pair that fits
 * one camera's image together and a third landmark for the other camera. */
std::vector<TObservation> enumerateObservations(const mrpt::math::TPose2D& pose,
                                                const std::vector<TLandmark>& lms,
                                                const std::vector<TLandmarkView>& views,
                                                const TCameraRig& rig);

}  // namespace risknav::viewpoint
