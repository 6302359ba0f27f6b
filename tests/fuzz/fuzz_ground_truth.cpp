// libFuzzer target: risknav-afraid-learn's groundtruth_file reader
// (readGroundTruth() in libs/afraid, the "t x y phi" lines risknav-simulate
// writes). The input is written to a temp file and read; every pose it
// yields must be finite with increasing times. Documented failure:
// CBadInputError. Anything else (another exception, a crash, a hang, a huge
// allocation) is a finding.
#include "fuzz_common.h"

#include <risknav/afraid/ground_truth.h>
#include <risknav/common/CBadInputError.h>

#include <cmath>
#include <cstdlib>

using namespace risknav;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = fuzz::tempPath("groundtruth.txt");
    fuzz::writeFile(path, data, size);
    std::vector<afraid::TGroundTruthPose> gt;
    try {
        gt = afraid::readGroundTruth(path);
    } catch (const common::CBadInputError&) {
        return 0;
    }
    for (size_t i = 0; i < gt.size(); i++) {
        for (const double v : gt[i])
            if (!std::isfinite(v))
                std::abort();  // a value no error could be computed from got through
        if (i > 0 && !(gt[i][0] > gt[i - 1][0]))
            std::abort();
    }
    return 0;
}
