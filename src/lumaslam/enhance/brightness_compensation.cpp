#include "lumaslam/enhance/brightness_compensation.h"

#include <algorithm>
#include <cmath>

namespace lumaslam::enhance {

double BrightnessCompensation::map(double l, double l_mean) const {
  const double lift_weight = params_.weights == CompensationWeights::kPaper ? l_mean : 1.0 - l_mean;
  const double value =
      lift_weight * std::pow(l, params_.alpha) + (1.0 - lift_weight) * std::pow(l, params_.beta);
  return std::clamp(value, 0.0, 1.0);
}

cv::Mat BrightnessCompensation::lookupTable(double l_mean) const {
  cv::Mat table(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i) {
    table.at<uchar>(i) = cv::saturate_cast<uchar>(255.0 * map(i / 255.0, l_mean));
  }
  return table;
}

cv::Mat BrightnessCompensation::apply(const cv::Mat& channel, double l_mean) const {
  cv::Mat out;
  cv::LUT(channel, lookupTable(l_mean), out);
  return out;
}

}  // namespace lumaslam::enhance
