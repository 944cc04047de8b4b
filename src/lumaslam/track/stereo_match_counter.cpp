#include "lumaslam/track/stereo_match_counter.h"

#include <algorithm>
#include <array>

#include "lumaslam/core/error.h"

namespace lumaslam::track {
namespace {

camera::StereoRectifier rectifierOf(const io::CalibrationHint& calibration) {
  if (!calibration.right || !calibration.T_left_right) {
    fail("stereo match count: the dataset has no stereo calibration (right camera, T_left_right)");
  }
  return camera::StereoRectifier(camera::PinholeCamera::fromSettings(calibration.left),
                                 camera::PinholeCamera::fromSettings(*calibration.right),
                                 *calibration.T_left_right);
}

feature::StereoMatcherParams matcherParams(const camera::StereoRectifier& rectifier) {
  feature::StereoMatcherParams params;
  params.bf = rectifier.bf();
  params.minDepth = rectifier.baseline();
  return params;
}

}  // namespace

StereoMatchCounter::StereoMatchCounter(const io::CalibrationHint& calibration,
                                       const feature::OrbSettings& orb)
    : rectifier_(rectifierOf(calibration)),
      extractor_(orb),
      matcher_(matcherParams(rectifier_), extractor_.levels()) {}

std::pair<cv::Mat, cv::Mat> StereoMatchCounter::rectify(const cv::Mat& left,
                                                        const cv::Mat& right) const {
  return rectifier_.rectify(left, right);
}

int StereoMatchCounter::matches(const cv::Mat& left_gray, const cv::Mat& right_gray) const {
  return matcher_.match(extractor_.extract(left_gray), extractor_.extract(right_gray)).matched;
}

}  // namespace lumaslam::track
