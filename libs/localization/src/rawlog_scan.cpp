#include <risknav/localization/rawlog_scan.h>

#include <mrpt/io/CFileGZInputStream.h>

#include <stdexcept>
#include <vector>

namespace risknav::localization {
TRawlogSize rawlogBytes(const std::string& path) {
    mrpt::io::CFileGZInputStream in;
    if (!in.open(path))
        throw std::runtime_error(path + ": cannot open rawlog");
    std::vector<unsigned char> block(1u << 20);
    TRawlogSize size;
    for (;;) {
        std::size_t n = 0;
        try {
            n = in.Read(block.data(), block.size());
        } catch (const std::exception&) {
            size.broken = true;
            break;
        }
        // MRPT passes gzread's -1 (a corrupt stream) on as a huge size_t:
        // looping on it never ends (a fuzzer finding)
        if (n > block.size()) {
            size.broken = true;
            break;
        }
        if (n == 0)
            break;
        size.bytes += n;
    }
    return size;
}
}  // namespace risknav::localization
