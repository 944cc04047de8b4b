#pragma once
// Enhancing a stereo pair as Enhancement.stereo says (docs/enhancement.md, Stereo): each image
// with its own plan (independent), or the right image with the left image's decisions or its
// whole plan. track::StereoMatchCounter measures what each mode does to stereo matching.
#include <utility>

#include <opencv2/core.hpp>

#include "lumaslam/enhance/enhancer.h"

namespace lumaslam::enhance {

// Enhances both images of a pair as left_enhancer.params().stereo says (independent: the
// right image with `right_enhancer`, on its own). Returns the two grays for tracking.
std::pair<cv::Mat, cv::Mat> enhanceStereoPair(Enhancer& left_enhancer, Enhancer& right_enhancer,
                                              const cv::Mat& left, const cv::Mat& right);

}  // namespace lumaslam::enhance
