#pragma once
// EPnP inside RANSAC (cv::solvePnPRansac) on 2D-3D matches, for poses found with no usable
// prior: relocalization, loop closing, and the tracker's reference-keyframe fallback.
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"

namespace lumaslam::camera {

struct PnpRansacParams {
  int iterations = 300;
  float reprojection_px = 4.0F;  // inlier threshold in undistorted level-0 pixels
  int min_inliers = 10;
};

struct PnpRansacResult {
  SE3 T_c_w = SE3::Identity();
  std::vector<bool> is_inlier;  // per input match
  int inliers = 0;
};

// `uv` are undistorted pixels of the points `X_w`, one per match. nullopt when RANSAC fails or
// finds fewer than params.min_inliers inliers.
std::optional<PnpRansacResult> solvePnpRansac(const std::vector<Eigen::Vector3d>& X_w,
                                              const std::vector<cv::Point2f>& uv,
                                              const CameraIntrinsics& k,
                                              const PnpRansacParams& params);

}  // namespace lumaslam::camera
