#pragma once
#include <risknav/common/TRobotOptions.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/rtti/CObject.h>

#include <optional>
#include <string>
#include <vector>

namespace risknav::common {
/** What a speed limiter sees in one control cycle. */
struct TSpeedLimitInput {
    const TRobotOptions* robot = nullptr;  ///< the robot (radius, decel, t_delay, ...)
    mrpt::math::TPose2D pose;              ///< where the robot believes it is
    double desiredSpeed = 0;               ///< [m/s] what the controller wants
    /** The latest scan (robot frame through its sensor pose); may be null. */
    const mrpt::obs::CObservation2DRangeScan* scan = nullptr;
    /** Sensed obstacle points in the robot frame (what MRPT's reactive
     * navigator senses, CReactiveNavigationSystem's obstacles); may be null. */
    const mrpt::maps::CSimplePointsMap* obstacles = nullptr;
    /** A second range sensor's latest scan (e.g. RANGE2); may be null. */
    const mrpt::obs::CObservation2DRangeScan* scan2 = nullptr;
    /** Where the robot is heading (the navigator's current target, world
     * frame); nullopt when it has none. */
    std::optional<mrpt::math::TPoint2D> target;
    /** [s] the controller's clock (simulated time in risknav's loops). */
    double time = 0;
    /** The path the controller is about to follow, robot frame, from the
     * robot's pose (0, 0, 0) on, with the distance [m] along it to each pose
     * (MRPT's chosen PTG trajectory); empty: unknown (limiters then assume
     * the straight line along the heading). */
    std::vector<mrpt::math::TPose2D> path;
    std::vector<double> pathDistance;
};

/** A limiter's answer: the highest speed it allows and why. */
struct TSpeedLimit {
    double maxSpeed = 0;  ///< [m/s], >= 0
    std::string reason;   ///< "" when it does not limit
};

/** Base of the speed-limiter plugins (the stopping-distance rule; later the
 * afraid map and the adaptive speed controller): each cycle every limiter
 * gives the highest speed it allows, and the smallest one wins. Plugins are
 * MRPT classes, created by name from a config through MRPT's class registry
 * (register them with the library's registerAllClasses_<lib>(), which also
 * works when risknav is linked statically). MRPT's plugin pattern: a public
 * non-virtual entry that checks its input and calls a protected virtual. */
class CSpeedLimiter : public mrpt::rtti::CObject {
    DEFINE_VIRTUAL_MRPT_OBJECT(CSpeedLimiter)
  public:
    /** Creates a limiter by class name ("CStoppingDistanceLimiter" or with
     * its namespace). Throws CBadInputError naming the known limiters when
     * the name is unknown or not a speed limiter. */
    static CSpeedLimiter::Ptr Factory(const std::string& className);
    /** Names of the registered limiters (for messages and --help). */
    static std::string knownNames();

    /** The limit for this cycle; throws std::invalid_argument on an input
     * without a robot or with a negative / non-finite desired speed. */
    TSpeedLimit limit(const TSpeedLimitInput& in) const;

    /** A new sensing cycle: called by the navigator once per cycle right
     * after it sensed, before its engine evaluates the motions, with the
     * cycle's pose, scans, target and time (no desired speed, no path: the
     * engine has not chosen them yet); limit() follows in the same cycle when
     * the engine commands a forward speed. A limiter whose work needs only
     * these may start it here (the adaptive limiter: its map and plans, on a
     * worker thread while the engine evaluates); finishObserved() ends it.
     * Default: nothing. Throws std::invalid_argument without a robot. */
    void observe(const TSpeedLimitInput& in) const;
    /** Waits for the work observe() started (the navigator calls it at the
     * end of each cycle, so that none outlives it); rethrows its error.
     * Default: nothing. */
    virtual void finishObserved() const {}

    /** Where a limiter that plans a way itself (the adaptive limiter's
     * path, on its own map) would have the robot steer from `pose`: a point
     * on that way `lookahead` [m] ahead, in the frame of the limiter's input
     * pose; nullopt (the default) when it plans none. From the last limit()
     * call. */
    virtual std::optional<mrpt::math::TPoint2D> guidePoint(
        const mrpt::math::TPose2D& pose, double lookahead) const {
        return std::nullopt;
    }

    /** The limiter's own options, in its own section. */
    virtual void loadConfig(const mrpt::config::CConfigFileBase& c,
                            const std::string& section) = 0;
    virtual void saveConfig(mrpt::config::CConfigFileBase& c,
                            const std::string& section) const = 0;

  protected:
    virtual TSpeedLimit impl_limit(const TSpeedLimitInput& in) const = 0;
    virtual void impl_observe(const TSpeedLimitInput&) const {}
};

/** Registers libs/common's MRPT classes (the plugin bases). Idempotent. */
void registerAllClasses_common();

}  // namespace risknav::common
