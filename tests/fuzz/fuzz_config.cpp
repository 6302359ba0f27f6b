// libFuzzer target: the config reader. The input is an .ini file; it is
// loaded by risknav::common::CIniConfig (MRPT preprocessor, duplicate-key and
// malformed-line checks), then the strict typed reads and a few options
// structs are loaded from it. Documented failures: CBadInputError (a
// std::runtime_error). Anything else escaping is a finding.
#include "fuzz_common.h"

#include <risknav/common/CBadInputError.h>
#include <risknav/common/CIniConfig.h>
#include <risknav/common/TOdometryOptions.h>
#include <risknav/common/TRobotOptions.h>
#include <risknav/common/config_read.h>
#include <risknav/common/grid_io.h>
#include <risknav/mapping/TObstacleRule.h>
#include <risknav/mapping/TSensorModel.h>
#include <risknav/risk/CRiskEvaluator.h>
#include <risknav/speed/TExploreOptions.h>
#include <risknav/speed/TSpeedControlOptions.h>

#include <cstdlib>
#include <set>
#include <stdexcept>

using namespace risknav;

namespace {
template <class F>
void tolerate(F&& f) {
    try {
        f();
    } catch (const std::runtime_error&) {  // CBadInputError and readers' errors
    }
}

/** One options struct loaded and validated from `section`. */
template <class OPTIONS>
void load(const common::CIniConfig& c, const char* section) {
    tolerate([&] {
        OPTIONS o;
        common::loadOptions(o, c, section);
    });
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = fuzz::tempPath("config.ini");
    fuzz::writeFile(path, data, size);
    tolerate([&] {
        common::CIniConfig c(path);
        for (const auto& s : c.sections())
            (void)s;
        // Each read separately, so that one bad key does not hide the others.
        load<common::TRobotOptions>(c, "Robot");
        load<common::TOdometryOptions>(c, "Odometry");
        for (const char* s : {"World", "RiskEval", "AfraidLearn"}) {
            load<mapping::TObstacleRule>(c, s);
            load<common::TMapSourceOptions>(c, s);
        }
        // risknav-risk-eval's routes and sensing points ([RouteN],
        // [SensingPointN]: names that become file names), through its own
        // loader (validate() before the map is loaded)
        tolerate([&] {
            risk::CRiskEvaluator ev;
            ev.loadFromConfigFile(c);
            std::set<std::string> files;
            for (const auto& r : ev.configRoutes)
                if (!files.insert(risk::CRiskEvaluator::ellipsesFileName(r.name))
                         .second ||
                    risk::CRiskEvaluator::covFileName(r.name, {}).size() >
                        common::kMaxOutputFileName)
                    std::abort();  // two routes' files would collide, or not fit
        });
        // risknav-explore's own sections (M1)
        load<speed::TExploreOptions>(c, "Explore");
        load<speed::TSpeedControlOptions>(c, "SpeedControl");
        for (const char* s : {"MapLaser", "MapRange2"})
            tolerate([&] {
                mapping::TSensorModel o;
                common::loadOptions(o, c, s);
                try {  // documented: no N for this model (the app says which key)
                    (void)mapping::necessaryObservations(o, 0.2);
                } catch (const std::invalid_argument&) {
                }
            });
        tolerate([&] {
            (void)common::readDouble(c, "Simulation", "sim_dt", 0.05,
                                     common::TRange::positive("s"));
        });
        tolerate([&] { (void)common::readInt(c, "Simulation", "seed", 7); });
        tolerate(
            [&] { (void)common::readBool(c, "World", "unknown_is_obstacle", true); });
        tolerate(
            [&] { (void)common::readNumbers(c, "Route", "waypoints", {}, {}, 4, 2); });
        tolerate([&] {
            (void)common::readChoice(c, "Odometry", "error_model", "systematic",
                                     {"systematic", "per_step", "none"});
        });
        tolerate([&] { (void)common::readDegrees(c, "Robot", "max_w_deg", 1.0, {}); });
        tolerate([&] { (void)common::readPath(c, "World", "map_file", "", false); });
        tolerate([&] { c.applyOverride("Robot.max_v=0.5"); });
        (void)c.unreadKeys();
        tolerate([&] { c.throwOnUnreadKeys(); });
    });
    return 0;
}
