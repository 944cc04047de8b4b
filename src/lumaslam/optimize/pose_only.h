#pragma once
// Pose-only optimisation (motion-only BA), run by the tracker on every frame: refines T_c_w
// from 2D-3D matches with the map points held fixed, ORB-SLAM's PoseOptimization with Ceres.
// Four rounds of (by default) 10 Levenberg-Marquardt iterations; after each round every
// observation is classified by chi-square (mono 5.991 / stereo 7.815), outliers are excluded
// from the next round and inliers (re-)included; the Huber kernel is dropped in the last round.
#include <vector>

#include <Eigen/Core>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/optimize/robust_thresholds.h"

namespace lumaslam::optimize {

struct PoseObservation {
  Eigen::Vector3d X_w = Eigen::Vector3d::Zero();  // the matched map point (world frame)
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();   // keypoint in the left/only image [px]
  double uRight = -1.0;    // column in the right image; < 0 means a monocular observation
  double invSigma2 = 1.0;  // 1 / sigma^2 of the keypoint's pyramid level
  bool isStereo() const { return uRight >= 0.0; }
};

struct PoseOnlyProblem {
  CameraIntrinsics camera{};
  SE3 T_c_w = SE3::Identity();  // initial guess
  std::vector<PoseObservation> observations{};
};

enum class DenseSolver {
  kNormalCholesky,  // 6x6 normal equations: ~15-25% faster here, the default
  kQR,              // ceres::DENSE_QR
};

enum class PoseBackend {
  kCeres,               // ceres::Solve with the residual layout and solver below
  kLevenbergMarquardt,  // pose_levenberg_marquardt.h: Ceres' per-observation HuberLoss model
                        // and trust-region rules on 6x6 normal equations, without Ceres
};

struct PoseOnlyOptions {
  int rounds = 4;
  int iterationsPerRound = 10;
  RobustThresholds thresholds{};
  // Fewer inliers than this after a round stops early, and at the end means failure.
  int minInliers = 10;
  // One Ceres residual block for all observations (pose_batch_cost.h, ~3x faster), or one
  // per observation with ceres::HuberLoss (the straightforward reference layout).
  bool batchResiduals = true;
  DenseSolver solver = DenseSolver::kNormalCholesky;
  PoseBackend backend = PoseBackend::kCeres;  // batchResiduals and solver apply to kCeres
};

struct PoseOnlyResult {
  SE3 T_c_w = SE3::Identity();    // refined pose; the initial guess when !success
  std::vector<bool> isOutlier{};  // one flag per observation, in input order
  int numInliers = 0;
  int iterations = 0;    // Levenberg-Marquardt iterations over all rounds
  bool success = false;  // false: too few observations or inliers to trust the pose
};

PoseOnlyResult optimizePose(const PoseOnlyProblem& problem, const PoseOnlyOptions& options = {});

}  // namespace lumaslam::optimize
