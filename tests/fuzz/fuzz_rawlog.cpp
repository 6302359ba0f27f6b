// libFuzzer target: the rawlog reader. The input is written as a rawlog file
// (plain or gz: MRPT's CFileGZInputStream reads both) and every frame is read.
// Documented failures: std::runtime_error (CBadInputError is one) naming the
// entry. Anything else escaping, a crash or a sanitizer report is a finding.
#include "fuzz_common.h"

#include <risknav/localization/CRawlogReader.h>

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = risknav::fuzz::tempPath("input.rawlog");
    risknav::fuzz::writeFile(path, data, size);
    try {
        risknav::localization::CRawlogReader r(path);
        size_t n = 0;
        while (auto f = r.next()) {
            // Touch what a consumer touches.
            if (f->sf)
                n += f->sf->size();
            if (f->actions)
                n += f->actions->size();
        }
        (void)n;
    } catch (const std::runtime_error&) {
    }
    return 0;
}
