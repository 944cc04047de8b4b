#pragma once
// Rotated ("steered") BRIEF of ORB: 256 intensity comparisons of the learned pattern rotated
// by the keypoint angle, sampled on a Gaussian-smoothed image.
#include <cstdint>

#include <opencv2/core.hpp>

namespace lumaslam::feature {

inline constexpr int kDescriptorBytes = 32;

// Writes 32 bytes to `descriptor`. `smoothed` is CV_8UC1 (7x7, sigma 2 Gaussian, as ORB);
// `point` must be at least 19 px from the border (the rotated pattern reaches 13*sqrt(2)).
void computeSteeredBrief(const cv::Mat& smoothed, cv::Point2f point, float angleDegrees,
                         std::uint8_t* descriptor);

// The smoothing ORB applies before sampling descriptors.
cv::Mat smoothForDescriptors(const cv::Mat& image);

}  // namespace lumaslam::feature
