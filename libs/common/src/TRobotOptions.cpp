#include <risknav/common/TRobotOptions.h>
#include <risknav/common/config_read.h>

namespace risknav::common {
void TRobotOptions::declare(Visitor& v) {
    v.number(radius, "radius", {0, 5, true, false, "m"}, "the robot is a disc");
    v.number(max_v, "max_v", {0, 5, true, false, "m/s"}, "top speed");
    v.number(max_w_deg, "max_w_deg", {0, 720, true, false, "deg/s"}, "top turn rate");
    v.number(accel, "accel", {0, 20, true, false, "m/s^2"}, "acceleration");
    v.number(decel, "decel", {0, 20, true, false, "m/s^2"},
             "braking; also the deceleration of the stopping distance");
    v.number(w_accel_deg, "w_accel_deg", {0, 10000, true, false, "deg/s^2"},
             "turn acceleration");
    v.number(t_delay, "t_delay", TRange::closed(0, 10, "s"),
             "maximum detection + reaction delay of the stopping distance");
}

}  // namespace risknav::common
