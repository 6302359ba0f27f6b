// risknav-navigate: MRPT's reactive navigation engine with risknav's speed
// limiters, driving a simulated world closed-loop (and the papers' experiments).
#include <risknav/common/CAppRunner.h>
#include <risknav/nav/navigate_app.h>

int main(int argc, char** argv) {
    const risknav::common::TAppInfo info{
        "risknav-navigate",
        "Drives a robot through a simulated world with MRPT's reactive navigator and "
        "risknav's speed limiters; writes the navlog, rawlog, trajectory and speed "
        "pictures, cycles.csv; or runs the afraid-map experiment.",
        ""};
    return risknav::common::runApp(argc, argv, info, risknav::nav::runNavigateApp);
}
