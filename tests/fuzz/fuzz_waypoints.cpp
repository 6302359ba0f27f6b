// libFuzzer target: risknav-navigate's route_file reader (an MRPT
// TWaypointSequence file, readWaypointFile() in libs/nav). The input is
// written to a temp file and read with a 0.15 m tolerance; every waypoint it
// yields must be finite with an allowed distance of at least that (and
// MRPT's speed ratio 1: others have no effect and are refused).
// Documented failure: CBadInputError. Anything else (another exception, a
// crash, a hang, a huge allocation) is a finding.
#include "fuzz_common.h"

#include <risknav/common/CBadInputError.h>
#include <risknav/nav/waypoint_file.h>

#include <cmath>
#include <cstdlib>

using namespace risknav;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = fuzz::tempPath("waypoints.ini");
    fuzz::writeFile(path, data, size);
    mrpt::nav::TWaypointSequence seq;
    std::map<size_t, nav::TWaypointTag> tags;
    try {
        nav::readWaypointFile(path, 0.15, seq, tags);
    } catch (const common::CBadInputError&) {
        return 0;
    }
    for (const auto& w : seq.waypoints)
        if (!std::isfinite(w.target.x) || !std::isfinite(w.target.y) ||
            !(w.allowed_distance >= 0.15) || w.speed_ratio != 1)
            std::abort();  // a value no run could use got through
    for (const auto& [i, t] : tags)
        if (i >= seq.waypoints.size())
            std::abort();
    return 0;
}
