#include <risknav/nav/CAdaptiveSpeedLimiter.h>
#include <risknav/nav/CAfraidSpeedLimiter.h>
#include <risknav/nav/CRiskAwareReactiveNav.h>
#include <risknav/sim/CStoppingDistanceLimiter.h>

namespace risknav::nav {
void registerAllClasses_nav() {
    sim::registerAllClasses_sim();
    mrpt::rtti::registerClass(CLASS_ID(CAfraidSpeedLimiter));
    mrpt::rtti::registerClass(CLASS_ID(CAdaptiveSpeedLimiter));
}

}  // namespace risknav::nav
