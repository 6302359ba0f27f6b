// risknav-afraid-learn: rawlogs + map -> where obstacles burst out (.afraid, zones, speed
// mask).
#include <risknav/afraid/afraid_report.h>
#include <risknav/common/CAppRunner.h>

int main(int argc, char** argv) {
    const risknav::common::TAppInfo info{"risknav-afraid-learn",
                                         "Learns from rawlogs (MCL on a known map) where "
                                         "obstacles appear abruptly (Choi, Chung, Song).",
                                         "[RAWLOG ...]"};
    return risknav::common::runApp(argc, argv, info, risknav::afraid::runAfraidLearnApp);
}
