#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>

namespace risknav::nav {
void registerAllClasses_nav() {
    sim::registerAllClasses_sim();
    mrpt::rtti::registerClass(CLASS_ID(CAfraidSpeedLimiter));
}

}  // namespace risknav::nav
