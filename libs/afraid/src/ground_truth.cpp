#include <risknav/afraid/ground_truth.h>
#include <risknav/common/CBadInputError.h>
#include <risknav/common/config_read.h>

#include <fstream>
#include <sstream>

using namespace risknav::common;

namespace risknav::afraid {
std::vector<TGroundTruthPose> readGroundTruth(const std::string& file) {
    std::vector<TGroundTruthPose> gt;
    std::ifstream f(file);
    // strictly: a line that is not 4 numbers, or a time that does not
    // increase, was dropped in silence (a NaN line; a file shifted 1e6 s)
    size_t lineNo = 0;
    for (std::string line; std::getline(f, line);) {
        lineNo++;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        const auto b = line.find_first_not_of(" \t");
        if (b == std::string::npos || line[b] == '%' || line[b] == '#')
            continue;
        const std::string where = file + ":" + std::to_string(lineNo) + ": ";
        auto bad = [&] {
            return CBadInputError(where + "expected 't x y phi' (4 numbers), got '" +
                                  line.substr(0, 80) + "'");
        };
        std::istringstream ls(line);
        TGroundTruthPose v{};
        size_t n = 0;
        for (std::string tok; ls >> tok; n++)
            if (n >= 4 || !parseNumber(tok, v[n]))
                throw bad();
        if (n != 4)
            throw bad();
        if (!gt.empty() && !(v[0] > gt.back()[0]))
            throw CBadInputError(where + "the times must increase");
        if (gt.size() >= 10000000)
            throw CBadInputError(where + "more than 1e7 lines");
        gt.push_back(v);
    }
    return gt;
}
}  // namespace risknav::afraid
