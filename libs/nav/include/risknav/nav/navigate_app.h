#pragma once
#include <risknav/common/CAppRunner.h>

namespace risknav::nav {
/** The risknav-navigate app body: one closed-loop run, or the afraid-map
 * experiment when the config has an [AfraidExperiment] section. */
void runNavigateApp(const common::TAppContext& ctx);

}  // namespace risknav::nav
