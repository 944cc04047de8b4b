#pragma once
// How many left features of a stereo pair find a stereo match (ORB + feature::StereoMatcher on
// the rectified pair, as track::FrameBuilder::buildStereo matches them): the measure behind
// `lumaslam enhance --evaluate-stereo` and docs/enhancement.md, Stereo.
#include <utility>

#include <opencv2/core.hpp>

#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/stereo_matcher.h"
#include "lumaslam/io/dataset_reader.h"

namespace lumaslam::track {

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

}  // namespace lumaslam::track
