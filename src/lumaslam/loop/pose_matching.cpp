#include "lumaslam/loop/pose_matching.h"

#include <algorithm>
#include <unordered_set>

#include "lumaslam/camera/pnp_ransac.h"
#include "lumaslam/core/error.h"
#include "lumaslam/feature/hamming.h"
#include "lumaslam/feature/projection_matcher.h"
#include "lumaslam/feature/rotation_histogram.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/optimize/pose_only.h"

namespace lumaslam::loop {

MatchingFrame matchingFrameOf(const map::KeyFrame& keyframe) {
  const auto& features = keyframe.features();
  if (!features.grid) fail("keyframe {}: features without a FeatureGrid", keyframe.id());
  return {&features, keyframe.intrinsics(), &keyframe.pyramid(), features.grid->bounds()};
}

int countMatches(const PointSlots& slots) {
  return static_cast<int>(
      std::count_if(slots.begin(), slots.end(), [](const auto& p) { return p != nullptr; }));
}

PointSlots searchByBow(const map::KeyFrame& keyframe, const FeatureVector& keyframe_nodes,
                       const map::FeatureSet& frame, const FeatureVector& frame_nodes, float ratio,
                       int max_distance) {
  PointSlots slots(frame.size());
  std::vector<int> matched_frame;
  std::vector<float> rotations;
  auto kf_node = keyframe_nodes.begin();
  auto f_node = frame_nodes.begin();
  const cv::Mat& kf_descriptors = keyframe.features().descriptors;
  while (kf_node != keyframe_nodes.end() && f_node != frame_nodes.end()) {
    if (kf_node->first < f_node->first) {
      ++kf_node;
      continue;
    }
    if (f_node->first < kf_node->first) {
      ++f_node;
      continue;
    }
    for (const int kf_index : kf_node->second) {
      const auto point = keyframe.mapPoint(static_cast<std::size_t>(kf_index));
      if (!point || point->isBad()) continue;
      int best = 256;
      int second = 256;
      int best_index = -1;
      for (const int f_index : f_node->second) {
        if (slots[static_cast<std::size_t>(f_index)]) continue;
        const int distance =
            feature::hammingDistance(kf_descriptors, kf_index, frame.descriptors, f_index);
        if (distance < best) {
          second = best;
          best = distance;
          best_index = f_index;
        } else if (distance < second) {
          second = distance;
        }
      }
      if (best_index < 0 || best > max_distance ||
          static_cast<float>(best) >= ratio * static_cast<float>(second)) {
        continue;
      }
      slots[static_cast<std::size_t>(best_index)] = point;
      matched_frame.push_back(best_index);
      rotations.push_back(keyframe.features().keypoints[static_cast<std::size_t>(kf_index)].angle -
                          frame.keypoints[static_cast<std::size_t>(best_index)].angle);
    }
    ++kf_node;
    ++f_node;
  }
  // Drop matches whose angle change disagrees with the dominant ones.
  const auto consistent = feature::rotationConsistentIndices(rotations);
  std::vector<bool> keep(matched_frame.size(), false);
  for (const std::size_t k : consistent) keep[k] = true;
  for (std::size_t k = 0; k < matched_frame.size(); ++k) {
    if (!keep[k]) slots[static_cast<std::size_t>(matched_frame[k])] = nullptr;
  }
  return slots;
}

bool solvePnpRansac(const MatchingFrame& frame, const PnpRansacParams& params, PointSlots& slots,
                    SE3& T_c_w) {
  std::vector<Eigen::Vector3d> X_w;
  std::vector<cv::Point2f> uv;
  std::vector<std::size_t> feature_of;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (!slots[i]) continue;
    X_w.push_back(slots[i]->position());
    uv.push_back(frame.features->undistorted[i]);
    feature_of.push_back(i);
  }
  const auto found = camera::solvePnpRansac(X_w, uv, frame.intrinsics, params);
  if (!found) return false;
  T_c_w = found->T_c_w;
  for (std::size_t m = 0; m < feature_of.size(); ++m) {
    if (!found->is_inlier[m]) slots[feature_of[m]] = nullptr;
  }
  return true;
}

int refinePose(const MatchingFrame& frame, PointSlots& slots, SE3& T_c_w) {
  optimize::PoseOnlyProblem problem;
  const auto& k = frame.intrinsics;
  problem.camera = {k.fx, k.fy, k.cx, k.cy, k.bf};
  problem.T_c_w = T_c_w;
  std::vector<std::size_t> feature_of;
  const map::FeatureSet& features = *frame.features;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (!slots[i]) continue;
    optimize::PoseObservation obs;
    obs.X_w = slots[i]->position();
    obs.uv = {features.undistorted[i].x, features.undistorted[i].y};
    obs.uRight = features.hasStereo(i) && k.bf > 0 ? features.u_right[i] : -1.0;
    const int octave = std::clamp(features.keypoints[i].octave, 0, frame.pyramid->count() - 1);
    obs.invSigma2 = frame.pyramid->inverseSigma2(octave);
    problem.observations.push_back(obs);
    feature_of.push_back(i);
  }
  optimize::PoseOnlyOptions options;
  options.backend = optimize::PoseBackend::kLevenbergMarquardt;  // as Tracker::optimizeCurrentPose
  const auto result = optimize::optimizePose(problem, options);
  if (!result.success) return 0;
  T_c_w = result.T_c_w;
  for (std::size_t m = 0; m < feature_of.size(); ++m) {
    if (result.isOutlier[m]) slots[feature_of[m]] = nullptr;
  }
  return result.numInliers;
}

int searchByProjection(const MatchingFrame& frame,
                       const std::vector<std::shared_ptr<map::MapPoint>>& points,
                       const std::vector<float>& angles, const SE3& T_c_w, float radius,
                       int max_distance, PointSlots& slots) {
  std::unordered_set<map::Id> found;
  for (const auto& p : slots) {
    if (p) found.insert(p->id());
  }
  const auto& k = frame.intrinsics;
  const Eigen::Vector3d center = T_c_w.inverse().translation();
  const bool check_rotation = !angles.empty();
  std::vector<feature::ProjectedPoint> projected;
  std::vector<std::shared_ptr<map::MapPoint>> source;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& point = points[i];
    if (!point || point->isBad() || found.contains(point->id())) continue;
    const Eigen::Vector3d X_w = point->position();
    const Eigen::Vector3d X_c = T_c_w * X_w;
    if (X_c.z() <= 0) continue;
    const cv::Point2f uv(static_cast<float>(k.fx * X_c.x() / X_c.z() + k.cx),
                         static_cast<float>(k.fy * X_c.y() / X_c.z() + k.cy));
    if (!frame.bounds.contains(uv)) continue;
    const double distance = (X_w - center).norm();
    if (distance < point->minDistance() || distance > point->maxDistance()) continue;
    feature::ProjectedPoint p;
    p.uv = uv;
    p.predictedLevel = point->predictScale(distance, *frame.pyramid);
    p.descriptor = point->descriptor();
    if (check_rotation) p.angle = angles[i];
    projected.push_back(p);
    source.push_back(point);
  }
  feature::ProjectionSearchOptions options;
  options.radius = radius;
  options.maxDistance = max_distance;
  options.ratio = 1.0F;
  options.checkRotation = check_rotation;
  const auto matches = feature::matchByProjection(
      projected, *frame.features->grid, frame.features->descriptors, *frame.pyramid, options);
  int added = 0;
  for (const auto& m : matches) {
    auto& slot = slots[static_cast<std::size_t>(m.trainIdx)];
    if (slot) continue;
    slot = source[static_cast<std::size_t>(m.queryIdx)];
    ++added;
  }
  return added;
}

}  // namespace lumaslam::loop
