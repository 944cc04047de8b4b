#pragma once
#include <opencv2/core.hpp>

namespace lumaslam {

// 8-bit gray of a 1-, 3- (BGR) or 4-channel (BGRA) image; a gray image is returned as is
// (shared, not copied).
cv::Mat toGray(const cv::Mat& image);

}  // namespace lumaslam
