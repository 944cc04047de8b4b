#include "lumaslam/enhance/stereo_enhancement.h"

namespace lumaslam::enhance {

std::pair<cv::Mat, cv::Mat> enhanceStereoPair(Enhancer& left_enhancer, Enhancer& right_enhancer,
                                              const cv::Mat& left, const cv::Mat& right) {
  const auto mapping = left_enhancer.params().stereo;
  if (mapping == StereoMapping::kIndependent) {
    return {left_enhancer.enhance(left).gray, right_enhancer.enhance(right).gray};
  }
  const EnhancementPlan plan = left_enhancer.plan(left);
  return {left_enhancer.apply(left, plan).gray, left_enhancer.enhanceRightWith(right, plan).gray};
}

}  // namespace lumaslam::enhance
