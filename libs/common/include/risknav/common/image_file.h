#pragma once
#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace risknav::common {
/** Writes an image to `path` in the format its extension names (".png").
 * Encoded in memory first, then written and checked as any output
 * (writeBytes()): a write failure (a full disk) is one std::runtime_error
 * naming the file and the system's reason, and the codec library prints
 * nothing of its own. */
void writeImageFile(const std::string& path, const cv::Mat& img,
                    const std::vector<int>& params = {});
}  // namespace risknav::common
