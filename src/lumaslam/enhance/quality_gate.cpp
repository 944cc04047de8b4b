#include "lumaslam/enhance/quality_gate.h"

#include <cmath>

namespace lumaslam::enhance {

BrightnessStats measureBrightness(const cv::Mat& channel) {
  CV_Assert(channel.type() == CV_8UC1 && !channel.empty());
  cv::Scalar mean;
  cv::Scalar stddev;
  cv::meanStdDev(channel, mean, stddev);
  return {mean[0] / 255.0, stddev[0] / 255.0};
}

bool QualityGate::needsCompensation(const BrightnessStats& stats) const {
  if (!params_.enabled) return true;
  const bool well_exposed =
      std::abs(stats.mean - 0.5) < params_.epsilon && stats.std > params_.theta;
  return !well_exposed;
}

}  // namespace lumaslam::enhance
