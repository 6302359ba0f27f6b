// risknav-explore: a robot in a world it does not know, at the fastest safe
// speed (Miura et al. 2006), compared with fixed speeds.
#include <risknav/common/CAppRunner.h>
#include <risknav/speed/explore_app.h>

int main(int argc, char** argv) {
    const risknav::common::TAppInfo info{"risknav-explore",
                                         "Explores an unknown world at the fastest safe "
                                         "speed (adaptive) and at fixed speeds; writes "
                                         "traces, speed profiles and snapshots.",
                                         ""};
    return risknav::common::runApp(argc, argv, info, risknav::speed::runExploreApp);
}
