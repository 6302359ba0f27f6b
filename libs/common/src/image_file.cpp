#include <risknav/common/COutputDir.h>
#include <risknav/common/image_file.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <stdexcept>

namespace risknav::common {
void writeImageFile(const std::string& path, const cv::Mat& img,
                    const std::vector<int>& params) {
    std::vector<uchar> bytes;
    bool ok = false;
    try {
        ok = cv::imencode(std::filesystem::path(path).extension().string(), img, bytes,
                          params);
    } catch (const cv::Exception&) {
        ok = false;
    }
    if (!ok)  // not the disk: an image OpenCV cannot encode (a bug of ours)
        throw std::logic_error("cannot encode the image " + shownOutputPath(path));
    writeBytes(path, std::string(bytes.begin(), bytes.end()));
}
}  // namespace risknav::common
