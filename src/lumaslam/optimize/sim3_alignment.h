#pragma once
// Refines the similarity S_12 between two keyframes from matched map points (ORB-SLAM's
// OptimizeSim3, used for monocular loop closing): each pair is a point of keyframe 1 and its
// match in keyframe 2, both in their camera's coordinates, with the keypoint each was seen at.
// Residuals: uv1 - pi(S_12 X2) and uv2 - pi(S_12^-1 X1), weighted by the keypoint's inverse
// level variance, under a Huber kernel. After a first solve, pairs above the chi-square
// threshold are dropped and the rest solved again. S_12 is parameterised as quaternion
// (ceres::EigenQuaternionManifold), translation and log-scale (so the scale stays positive).
#include <vector>

#include <Eigen/Core>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/optimize/sim3.h"

namespace lumaslam::optimize {

struct Sim3Pair {
  Eigen::Vector3d X1 = Eigen::Vector3d::Zero();   // in camera 1
  Eigen::Vector3d X2 = Eigen::Vector3d::Zero();   // in camera 2
  Eigen::Vector2d uv1 = Eigen::Vector2d::Zero();  // where X2's match is seen in image 1
  Eigen::Vector2d uv2 = Eigen::Vector2d::Zero();  // where X1's match is seen in image 2
  double invSigma2_1 = 1.0;
  double invSigma2_2 = 1.0;
};

struct Sim3AlignmentOptions {
  int iterations = 5;                         // per round (ORB-SLAM: 5 + 5)
  double chi2 = 10.0;                         // per image (ORB-SLAM's OptimizeSim3 threshold)
  const CameraIntrinsics* camera2 = nullptr;  // null: the same camera for both images
};

struct Sim3AlignmentResult {
  Sim3 S_12{};
  std::vector<bool> inlier{};  // per pair
  int inliers = 0;
};

// Squared reprojection errors (times invSigma2) of a pair in image 1 and image 2.
Eigen::Vector2d sim3PairChi2(const Sim3& S_12, const Sim3Pair& pair,
                             const CameraIntrinsics& camera1, const CameraIntrinsics& camera2);

Sim3AlignmentResult refineSim3(const std::vector<Sim3Pair>& pairs, const Sim3& initial,
                               const CameraIntrinsics& camera,
                               const Sim3AlignmentOptions& options = {});

}  // namespace lumaslam::optimize
