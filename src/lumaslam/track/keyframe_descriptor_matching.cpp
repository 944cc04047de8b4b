#include "lumaslam/track/keyframe_descriptor_matching.h"

#include "lumaslam/feature/descriptor_matcher.h"
#include "lumaslam/feature/rotation_histogram.h"

namespace lumaslam::track {

std::vector<std::shared_ptr<map::MapPoint>> matchKeyFramePoints(const map::KeyFrame& keyframe,
                                                                const map::FeatureSet& frame,
                                                                const KeyFrameMatchParams& params) {
  std::vector<std::shared_ptr<map::MapPoint>> slots(frame.size());
  const auto points = keyframe.mapPoints();
  const auto& kf_features = keyframe.features();
  std::vector<int> kf_index;  // train row -> keyframe feature
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i] && !points[i]->isBad()) kf_index.push_back(static_cast<int>(i));
  }
  if (kf_index.empty() || frame.size() == 0) return slots;
  cv::Mat train(static_cast<int>(kf_index.size()), kf_features.descriptors.cols, CV_8U);
  std::vector<cv::KeyPoint> train_keypoints;
  train_keypoints.reserve(kf_index.size());
  for (std::size_t r = 0; r < kf_index.size(); ++r) {
    kf_features.descriptors.row(kf_index[r]).copyTo(train.row(static_cast<int>(r)));
    train_keypoints.push_back(kf_features.keypoints[static_cast<std::size_t>(kf_index[r])]);
  }
  feature::MatchOptions options;
  options.maxDistance = params.max_distance;
  options.ratio = params.ratio;
  options.crossCheck = true;
  const auto matches = feature::filterByRotationConsistency(
      feature::matchBruteForce(frame.descriptors, train, options), frame.keypoints,
      train_keypoints);
  for (const auto& m : matches) {
    slots[static_cast<std::size_t>(m.queryIdx)] =
        points[static_cast<std::size_t>(kf_index[static_cast<std::size_t>(m.trainIdx)])];
  }
  return slots;
}

}  // namespace lumaslam::track
