#pragma once
// How enhancement changes stereo matching (docs/enhancement.md, Stereo): a rectified pair is
// enhanced independently (each image its own plan), with the left image's decisions, or with
// the left image's whole plan; then ORB + StereoMatcher count the matched left features.
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/stereo_matcher.h"
#include "lumaslam/io/dataset_reader.h"

namespace lumaslam {

// Enhances both images of a pair as left_enhancer.params().stereo says (independent: the
// right image with `right_enhancer`, on its own). Returns the two grays for tracking.
std::pair<cv::Mat, cv::Mat> enhanceStereoPair(enhance::Enhancer& left_enhancer,
                                              enhance::Enhancer& right_enhancer,
                                              const cv::Mat& left, const cv::Mat& right);

class StereoMatchCounter {
 public:
  // Needs a stereo calibration (right camera and T_left_right); throws Error otherwise.
  StereoMatchCounter(const io::CalibrationHint& calibration, const feature::OrbSettings& orb);

  // Rectified pair of the calibrated size.
  std::pair<cv::Mat, cv::Mat> rectify(const cv::Mat& left, const cv::Mat& right) const;
  // Stereo-matched left features of two rectified 8-bit gray images.
  int matches(const cv::Mat& left_gray, const cv::Mat& right_gray) const;

 private:
  camera::StereoRectifier rectifier_;
  feature::OrbExtractor extractor_;
  feature::StereoMatcher matcher_;
};

}  // namespace lumaslam
