#pragma once
#include <risknav/risk/CObstacleField.h>
#include <risknav/risk/odometry_covariance.h>

#include <mrpt/math/TPoint2D.h>

#include <Eigen/Dense>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace risknav::risk {
/** How a route is driven and how its risk is integrated. */
struct TRiskOptions {
    TOdometryModel odometry;
    TErrorModel model = TErrorModel::Systematic;
    /** How the pose error is propagated (the [Odometry] default, chosen by
     * measurement: see TPropagationOptions). */
    TPropagation propagation = TPropagation::Cubature5;
    int samples = 1000;  ///< draws of TPropagation::Sampled
    uint64_t seed = 1;   ///< seed of TPropagation::Sampled
    Eigen::Matrix3d sigmaP0 =
        Eigen::Matrix3d::Zero();  ///< initial pose covariance (x y theta)
    double tau = 0.05;            ///< [s] propagation step
    double speed = 0.3;           ///< [m/s] on straight legs
    double turnRate = 0.5;        ///< [rad/s] turns in place at waypoints
    double evalStep = 0.05;       ///< [m] D_max / u sampling along the path
};

/** A place where the robot observes landmarks (ceiling images in the paper):
 * passing within `radius` resets the pose covariance to `resetCov`
 * (Irie et al. section 5.1 / 6.4). */
struct TSensingPoint {
    std::string name;
    double x = 0, y = 0, radius = 0.1;
    Eigen::Matrix3d resetCov = Eigen::Matrix3d::Zero();
};

/** One evaluation sample along the path. */
struct TRiskSample {
    double s = 0;                    ///< arc length [m]
    double x = 0, y = 0, theta = 0;  ///< the planned pose
    /** E[(p - plan)(p - plan)^T] of the pose (x y theta): the covariance plus
     * bias bias^T (CPosePropagator::secondMoment()); its x-y block gives D_max. */
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    Eigen::Vector3d bias = Eigen::Vector3d::Zero();  ///< mean pose - plan
    TDmax dmax;
    double u = 0;  ///< eq. (29), 1 / D_max^2
    bool sensedHere = false;
};

struct TRiskResult {
    std::vector<TRiskSample> samples;
    std::vector<std::string> sensed;  ///< sensing points used, in order
    double length = 0;                ///< [m]
    double U = 0;                     ///< eq. (30), trapezoid rule over the samples
    double uMax = 0;
    double sMaxU = 0;      ///< where u peaks [m]
    bool blocked = false;  ///< the robot centre entered a grown obstacle (D_max = 0)
    /** Not empty when the covariance overflowed (not finite): the evaluation
     * stopped there, U and uMax are +inf (never a finite or zero risk read
     * from an overflow). */
    std::string failure;
};

/** One propagation step of the motion along a path: the commanded wheel speeds
 * [rad/s] for a duration tau, starting at heading theta; (x, y, s) at its end. */
struct TMotionStep {
    double theta = 0, uL = 0, uR = 0, tau = 0;
    double x = 0, y = 0, s = 0;
    bool turning = false;
};

/** The path as a feasible motion for a differential drive: start facing the
 * first leg, turn in place at each waypoint at turnRate, drive legs straight
 * at speed; steps of tau (the last step of a turn or leg is shorter). Calls
 * `visit` for each step in order (nothing is stored). */
void forEachMotionStep(const std::vector<mrpt::math::TPoint2D>& path,
                       const TOdometryModel& m, double speed, double turnRate, double tau,
                       const std::function<void(const TMotionStep&)>& visit);
/** forEachMotionStep()'s steps, as a vector. */
std::vector<TMotionStep> motionProfile(const std::vector<mrpt::math::TPoint2D>& path,
                                       const TOdometryModel& m, double speed,
                                       double turnRate, double tau);

/** How many propagation steps the motion of a path takes, without making
 * them: straight = sum over legs of ceil(length / (speed tau)), turning = sum
 * over turns of ceil(|angle| / (turnRate tau)) (an upper bound of
 * forEachMotionStep()'s count, by at most one per leg and turn). */
struct TStepCount {
    double straight = 0, turning = 0;
    double total() const { return straight + turning; }
};
TStepCount motionStepCount(const std::vector<mrpt::math::TPoint2D>& path, double speed,
                           double turnRate, double tau);

/** u(x) = 1 / D_max(x)^2, eq. (29). D_max = inf (no obstacle) gives 0;
 * D_max = 0 (in collision) gives +inf. */
double riskDensity(double dmax);

/** U = integral of u ds by the trapezoid rule, eq. (30). Samples with u = inf
 * make U inf. */
double integrateRisk(const std::vector<double>& s, const std::vector<double>& u);

/** Drives the polyline: starts facing the first leg, turns in place at each
 * waypoint at turnRate, drives straight legs at speed; the commanded wheel
 * speeds of each tau step propagate the pose error (CPosePropagator: per_step
 * eq. 15 or systematic, linear or by sigma points). Selected sensing points
 * reset the covariance when the robot comes within their radius (once each).
 * u is sampled every evalStep metres (and at both ends), from D_max of the
 * second moment about the plan (eq. 28 centred on the path). A covariance
 * that is not finite stops the evaluation with `failure` set. */
TRiskResult evaluatePathRisk(const std::vector<mrpt::math::TPoint2D>& path,
                             const std::vector<TSensingPoint>& sensing,
                             const CObstacleField& field, const TRiskOptions& opt);

/** The route with detours to the given sensing points: each point is joined to
 * the nearest point P of the route (as the paper joins sensing points to the
 * nearest GVG point); the path goes P -> sensing point -> P there, unless the
 * route already passes within the point's radius. Returns false (and leaves
 * `out` empty) when a detour would cross a grown obstacle. */
bool routeWithSensingDetours(const std::vector<mrpt::math::TPoint2D>& route,
                             const std::vector<TSensingPoint>& visit,
                             const CObstacleField& field,
                             std::vector<mrpt::math::TPoint2D>& out);

}  // namespace risknav::risk
