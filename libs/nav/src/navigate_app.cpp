#include <risknav/common/summary_json.h>
#include <risknav/nav/CAfraidExperiment.h>
#include <risknav/nav/CNavigationRun.h>
#include <risknav/nav/navigate_app.h>
#include <risknav/nav/navigate_report.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>

using namespace risknav::common;
namespace fs = std::filesystem;

namespace risknav::nav {
namespace {
void runSingle(const TAppContext& ctx) {
    CNavigationRun nr;
    nr.loadFromConfigFile(ctx.cfg, ctx.args.seed);
    // (what is in the way of an output refused before the run, not after it)
    COutputDir out(ctx.args.outDir, ctx.info.name,
                   {"cycles.csv", "events.csv", "trajectory.png", "speed_profile.png"});
    // MRPT writes its navlog into a folder of its own: one in the run's
    // staging area (the same file system: the file is renamed into its staged
    // name), removed with it, also by the next run after a kill.
    const std::string navlogScratch = out.scratchDir("navlog");
    TNavRunSetup setup;
    setup.seed = nr.options.seed;
    setup.quiet = ctx.args.quiet;
    if (nr.options.navlog)
        setup.navlogDir = navlogScratch;
    if (nr.options.rawlog) {
        setup.rawlogPath = out.stage("navigation.rawlog");
        setup.groundtruthPath = out.stage("groundtruth.txt");
    }
    const TNavRunResult r = nr.run(setup);
    if (nr.options.navlog) {
        if (r.navlogFile.empty())
            throw std::runtime_error("MRPT wrote no .reactivenavlog");
        fs::rename(r.navlogFile, out.stage("navigation.reactivenavlog"));
    }
    writeCyclesCsv(r, nr.options.start_time, out.stage("cycles.csv"));
    writeEventsCsv(r, nr.options.start_time, out.stage("events.csv"));
    char title[300];
    std::snprintf(title, sizeof(title),
                  "risknav-navigate: %s  |  %s, %.1f s, %.1f m, %d collisions, %d near "
                  "misses",
                  fs::path(nr.world.mapSource.map_file).filename().c_str(),
                  r.status.c_str(), r.time, r.distance, r.collisions(),
                  r.safety.nearMisses());
    drawTrajectory(nr, r, title, out.stage("trajectory.png"));
    drawSpeedProfile(r, title, out.stage("speed_profile.png"));
    nlohmann::json summary = summaryHeader(ctx, nr.options.seed);
    summary.update(runSummary(nr, r));
    mrpt::config::CConfigFileMemory effective;
    nr.saveToConfigFile(effective);
    commitRun(ctx, out, summary, effective);
    if (!ctx.args.quiet)
        std::fprintf(stderr, "%s: %s, %.1f s simulated, %.1f m, %d collisions -> %s\n",
                     ctx.info.name.c_str(), r.status.c_str(), r.time, r.distance,
                     r.collisions(), out.dir().c_str());
}
}  // namespace

void runNavigateApp(const TAppContext& ctx) {
    if (ctx.cfg.sectionExists("AfraidExperiment"))
        runAfraidExperiment(ctx);
    else
        runSingle(ctx);
}

}  // namespace risknav::nav
