#pragma once
// Synthetic optimisation problems with known ground truth, for tests and benchmarks:
// points seen by a rectified stereo camera (EuRoC-like intrinsics), pixel noise scaled by a
// pyramid level, gross outliers, and perturbed initial estimates. Deterministic per seed.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/core/pose.h"
#include "lumaslam/optimize/local_ba.h"
#include "lumaslam/optimize/pose_only.h"

namespace lumaslam::optimize {

// 752x480, fx = fy = 458, baseline 11 cm (EuRoC cam0/cam1).
CameraIntrinsics syntheticCamera();
inline constexpr int kSyntheticImageWidth = 752;
inline constexpr int kSyntheticImageHeight = 480;

struct SyntheticNoise {
  double pixelSigma = 1.0;  // at pyramid level 0; level l has sigma * scale^l
  int pyramidLevels = 1;    // levels drawn uniformly in [0, pyramidLevels)
  double pyramidScale = 1.2;
  double outlierRatio = 0.2;       // share of observations replaced by a wrong match
  double minOutlierOffset = 30.0;  // [px] a wrong match is at least this far from the truth
};

struct SyntheticPoseOnlySpec {
  int numObservations = 300;
  bool stereo = false;
  SyntheticNoise noise{};
  double initialTranslationError = 0.05;  // [m]
  double initialRotationErrorDeg = 3.0;
  std::uint32_t seed = 1;
};

struct SyntheticPoseOnly {
  PoseOnlyProblem problem;  // problem.T_c_w is the perturbed initial guess
  SE3 T_c_w_true = SE3::Identity();
  std::vector<bool> isInjectedOutlier{};
};

SyntheticPoseOnly makeSyntheticPoseOnly(const SyntheticPoseOnlySpec& spec);

struct SyntheticBundleSpec {
  int numKeyFrames = 10;
  int numPoints = 500;
  int numFixedKeyFrames = 2;  // the first ones along the path, left at the ground truth
  int minObservations = 3;    // points are drawn until each is seen by this many keyframes
  bool stereo = false;
  SyntheticNoise noise{.outlierRatio = 0.05};
  double poseTranslationError = 0.05;  // [m] on the free keyframes
  double poseRotationErrorDeg = 1.0;
  double pointError = 0.1;  // [m] per axis, on every point
  std::uint32_t seed = 1;
};

struct SyntheticBundle {
  LocalBAProblem problem;  // perturbed poses (free keyframes) and points
  std::vector<SE3> T_c_w_true;
  std::vector<Eigen::Vector3d> X_w_true;
  std::vector<bool> isInjectedOutlier{};
};

SyntheticBundle makeSyntheticBundle(const SyntheticBundleSpec& spec);

// Left-perturbs a pose by a random rotation of `rotationDeg` and translation of `translation`.
SE3 perturbPose(const SE3& T, double translation, double rotationDeg, std::uint32_t seed);

}  // namespace lumaslam::optimize
