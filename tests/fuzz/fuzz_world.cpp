// libFuzzer target: the polygon world reader of the viewpoint planner (M4).
// The input is a world text file (bounds / obstacle / hole / landmark lines,
// TPolygonWorld.h). It is parsed with parsePolygonWorld(text, "fuzz", false)
// and, when it parses, checked with validateWorld() and its derived data
// (the edges, the inside test at each landmark, the obstacles' reference
// points) computed, as CViewpointPlanner::setWorld() does next. Inputs whose
// size is a multiple of 4, and every input holding a NUL byte, also go
// through loadPolygonWorld() on a temp file (the file path's size and binary
// checks, bounds required). Documented failure: CBadInputError. Anything
// else (another exception, a crash, a hang, a huge allocation) is a finding.
#include "fuzz_common.h"

#include <risknav/common/CBadInputError.h>
#include <risknav/viewpoint/TPolygonWorld.h>

#include <string>

using namespace risknav;

namespace {
void check(const viewpoint::TPolygonWorld& w) {
    try {
        viewpoint::validateWorld(w, "fuzz");
    } catch (const common::CBadInputError&) {
        return;
    }
    (void)w.edges().size();
    for (const auto& l : w.landmarks)
        (void)w.insideObstacle({l.x, l.y});
    (void)w.obstacleReferencePoints().size();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        check(viewpoint::parsePolygonWorld(text, "fuzz", false));
    } catch (const common::CBadInputError&) {
    }
    if (size % 4 == 0 || text.find('\0') != std::string::npos) {
        static const std::string path = fuzz::tempPath("world.txt");
        fuzz::writeFile(path, data, size);
        try {
            check(viewpoint::loadPolygonWorld(path));
        } catch (const common::CBadInputError&) {
        }
    }
    return 0;
}
