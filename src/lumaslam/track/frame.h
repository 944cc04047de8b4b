#pragma once
// One tracked image: its features (shared with the keyframe it may become), the map points
// matched to them, and the estimated pose. Owned by the tracker; never shared across threads.
#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/map/feature_set.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map_point.h"

namespace lumaslam::track {

struct Frame {
  std::size_t index = 0;
  double timestamp = 0.0;
  std::shared_ptr<map::FeatureSet> features;
  std::vector<std::shared_ptr<map::MapPoint>> points;  // per feature, null if unmatched
  std::vector<bool> outliers;                          // per feature
  std::optional<SE3> T_c_w;
  std::shared_ptr<map::KeyFrame> reference;
  std::vector<cv::Rect2f> dynamic_boxes;  // moving objects detected in this image (pixels)
  // Per feature, log-odds that it is static (MotionEvidence); empty until the pose is known.
  std::vector<float> static_log_odds;

  std::size_t size() const { return features ? features->size() : 0; }
  void clearMatches() {
    points.assign(size(), nullptr);
    outliers.assign(size(), false);
  }
  // Camera-frame point of a feature with depth (undistorted pixel back-projected).
  Eigen::Vector3d unprojectCamera(std::size_t i, const CameraIntrinsics& k) const {
    const auto& p = features->undistorted[i];
    const double z = features->depth[i];
    return {(p.x - k.cx) * z / k.fx, (p.y - k.cy) * z / k.fy, z};
  }
};

}  // namespace lumaslam::track
