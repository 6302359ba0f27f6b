#pragma once
#include <mrpt/obs/CObservation2DRangeScan.h>

namespace risknav::common {
/** What a navigator may want from a robot beyond MRPT's CRobot2NavInterface,
 * for a robot that senses with 2D range scanners: an optional interface any
 * robot (simulated or real) may implement next to CRobot2NavInterface. A
 * navigator asks for it with dynamic_cast and works without it.
 *
 * risknav::nav::CRiskAwareReactiveNav uses it so that its speed limiters
 * observe the cycle's scans before MRPT's engine senses (senseAhead()), and
 * so that they see the raw scans, rays and not only end points (lastScan(),
 * lastScan2(): the adaptive limiter maps free space along the rays). A robot
 * without it: the limiters observe once MRPT has sensed, on MRPT's obstacle
 * points alone (no scans), as MRPT evaluates its motions.
 *
 * The robot's shape is not asked here: the navigator takes MRPT's own
 * (its config, or changeRobotShape()). */
class CRangeSensingRobot {
  public:
    virtual ~CRangeSensingRobot() = default;

    /** Senses now the scans that the next CRobot2NavInterface::
     * senseObstacles() returns (that call must then not sense again; a
     * second senseAhead() before it senses nothing new): lets a navigator
     * start work on a cycle's scans before its engine's sensing, without
     * sensing twice. */
    virtual void senseAhead() = 0;
    /** The latest sensing's scan of the main range sensor (robot frame
     * through its sensor pose); null when none yet. */
    virtual const mrpt::obs::CObservation2DRangeScan* lastScan() const = 0;
    /** The latest sensing's scan of a second range sensor; null when the
     * robot has none. */
    virtual const mrpt::obs::CObservation2DRangeScan* lastScan2() const = 0;

  protected:
    CRangeSensingRobot() = default;
    CRangeSensingRobot(const CRangeSensingRobot&) = default;
    CRangeSensingRobot& operator=(const CRangeSensingRobot&) = default;
};
}  // namespace risknav::common
