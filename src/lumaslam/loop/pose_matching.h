#pragma once
// Matching and pose steps shared by relocalization and loop closing (ORB-SLAM's
// SearchByBoW, EPnP + RANSAC, pose-only refinement and SearchByProjection against a frame
// with no reliable pose prior). A "frame" is any feature set with its camera: a tracked
// frame being relocalized or the keyframe that closes a loop.
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/camera/pnp_ransac.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/loop/bow_vector.h"
#include "lumaslam/map/feature_set.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map_point.h"

namespace lumaslam::loop {

// Per feature of the frame: the map point it is matched to, or null.
using PointSlots = std::vector<std::shared_ptr<map::MapPoint>>;

struct MatchingFrame {
  const map::FeatureSet* features = nullptr;
  CameraIntrinsics intrinsics;
  const feature::ScaleLevels* pyramid = nullptr;
  cv::Rect2f bounds;  // where undistorted keypoints can lie (projection search)
};

// A keyframe seen as a MatchingFrame (bounds from its FeatureGrid, which it must have).
MatchingFrame matchingFrameOf(const map::KeyFrame& keyframe);

int countMatches(const PointSlots& slots);

// Features of `frame` matched to `keyframe`'s map points within the same vocabulary node;
// nearest neighbour under `max_distance` with a ratio test, then rotation consistency.
PointSlots searchByBow(const map::KeyFrame& keyframe, const FeatureVector& keyframe_nodes,
                       const map::FeatureSet& frame, const FeatureVector& frame_nodes, float ratio,
                       int max_distance);

using PnpRansacParams = camera::PnpRansacParams;

// EPnP inside RANSAC on the matched points; only the inliers stay in `slots`.
bool solvePnpRansac(const MatchingFrame& frame, const PnpRansacParams& params, PointSlots& slots,
                    SE3& T_c_w);

// Pose-only refinement (mono and stereo reprojection with robust kernels); outliers are
// removed from `slots`. Returns the number of inliers (0 on failure).
int refinePose(const MatchingFrame& frame, PointSlots& slots, SE3& T_c_w);

// Points not matched yet, projected with T_c_w and matched in a window of `radius` px.
// `angles`: the keypoint angle of each point in the view it comes from, for the rotation
// check; empty = no rotation check. Returns the number of matches added to `slots`.
int searchByProjection(const MatchingFrame& frame,
                       const std::vector<std::shared_ptr<map::MapPoint>>& points,
                       const std::vector<float>& angles, const SE3& T_c_w, float radius,
                       int max_distance, PointSlots& slots);

}  // namespace lumaslam::loop
