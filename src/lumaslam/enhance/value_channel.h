#pragma once
// HSV value channel (paper Eq. 5-8) and the colour rebuild that keeps hue and saturation.
// Both are single passes with OpenCV's universal intrinsics (SIMD where the build has it).
#include <opencv2/core.hpp>

namespace lumaslam::enhance {

// V = max(B, G, R) of an 8-bit BGR image (CV_8UC1 result).
cv::Mat valueChannel(const cv::Mat& bgr);
void valueChannel(const cv::Mat& bgr, cv::Mat& value);

// Scales each pixel's BGR by channel_new / channel_old (rounded half to even, saturated). When
// channel_old = max(B, G, R), hue and saturation (Eq. 6-7) are kept and the new V equals
// channel_new; a pixel with channel_old = 0 becomes gray at channel_new.
cv::Mat rebuildColour(const cv::Mat& bgr, const cv::Mat& channel_old, const cv::Mat& channel_new);
void rebuildColour(const cv::Mat& bgr, const cv::Mat& channel_old, const cv::Mat& channel_new,
                   cv::Mat& out);

}  // namespace lumaslam::enhance
