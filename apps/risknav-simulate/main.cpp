// risknav-simulate: a world .ini -> MRPT rawlog, ground truth, events, picture.
#include <risknav/common/CAppRunner.h>
#include <risknav/sim/CWorldSimulator.h>

int main(int argc, char** argv) {
    const risknav::common::TAppInfo info{"risknav-simulate",
                                         "Simulates a robot driving a route through a "
                                         "world with people; writes an MRPT rawlog.",
                                         ""};
    return risknav::common::runApp(argc, argv, info, risknav::sim::runSimulateApp);
}
