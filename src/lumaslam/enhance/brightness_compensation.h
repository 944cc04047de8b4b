#pragma once
// Dynamic brightness compensation of paper Eq. 4, applied through a 256-entry lookup table.
#include <opencv2/core.hpp>

#include "lumaslam/enhance/enhancer_params.h"

namespace lumaslam::enhance {

class BrightnessCompensation {
 public:
  explicit BrightnessCompensation(const CompensationParams& params) : params_(params) {}

  // Eq. 4 for one normalised value l in [0, 1] given the frame's Lmean.
  double map(double l, double l_mean) const;
  // The 8-bit table of map() for this Lmean (CV_8UC1, 1x256).
  cv::Mat lookupTable(double l_mean) const;
  // Applies the table to an 8-bit single-channel image.
  cv::Mat apply(const cv::Mat& channel, double l_mean) const;

 private:
  CompensationParams params_;
};

}  // namespace lumaslam::enhance
