// risknav-viewpoint-plan: paths, viewpoints and observation strategies (M4).
#include <risknav/common/CAppRunner.h>
#include <risknav/viewpoint/viewpoint_report.h>

int main(int argc, char** argv) {
    const risknav::common::TAppInfo info{
        "risknav-viewpoint-plan",
        "Plans a path and the viewpoints along it, choosing stereo, two- or "
        "three-landmark observation at each (Yamashita et al.).",
        ""};
    return risknav::common::runApp(argc, argv, info,
                                   risknav::viewpoint::runViewpointPlanApp);
}
