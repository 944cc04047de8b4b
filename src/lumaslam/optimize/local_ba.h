#pragma once
// Local bundle adjustment (ORB-SLAM's LocalBundleAdjustment with Ceres): the local keyframes'
// poses and the points they see are refined jointly; outer covisible keyframes that also see
// those points enter as fixed poses (the gauge). Huber kernels during the solve, then every
// observation is classified by chi-square so the mapper can erase the bad ones.
// Solved with a Schur complement (points eliminated first); see docs/optimization.md for the
// SPARSE_SCHUR / ITERATIVE_SCHUR / DENSE_SCHUR measurements.
#include <atomic>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/optimize/robust_thresholds.h"

namespace lumaslam::optimize {

struct BAKeyFrame {
  std::uint64_t id = 0;
  SE3 T_c_w = SE3::Identity();
  bool fixed = false;
};

struct BAPoint {
  std::uint64_t id = 0;
  Eigen::Vector3d X_w = Eigen::Vector3d::Zero();
};

struct BAObservation {
  std::uint64_t keyFrameId = 0;
  std::uint64_t pointId = 0;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  double uRight = -1.0;  // < 0: monocular observation
  double invSigma2 = 1.0;
  bool isStereo() const { return uRight >= 0.0; }
};

struct LocalBAProblem {
  CameraIntrinsics camera{};
  std::vector<BAKeyFrame> keyFrames{};
  std::vector<BAPoint> points{};
  std::vector<BAObservation> observations{};
};

enum class SchurSolver { kSparse, kIterative, kDense };

struct LocalBAOptions {
  int maxIterations = 10;  // robust (Huber) stage over all observations
  // Second stage as in ORB-SLAM2: the first stage's chi-square outliers are excluded and the
  // kernel dropped for this many more iterations (0 = ORB-SLAM3's single stage).
  int refinementIterations = 10;
  double maxSolverTimeSeconds = 1e6;  // wall-clock budget of both stages together
  // Set by the mapper (another thread) to stop early: checked before the solve and after every
  // iteration; the best state reached so far is returned.
  const std::atomic<bool>* abort = nullptr;
  SchurSolver solver = SchurSolver::kSparse;
  RobustThresholds thresholds{};
};

struct LocalBAResult {
  std::vector<SE3> T_c_w;            // per keyframe, input order (fixed ones unchanged)
  std::vector<Eigen::Vector3d> X_w;  // per point, input order
  std::vector<bool> isOutlier{};     // per observation: chi-square too large or behind camera
  int numOutliers = 0;
  int iterations = 0;        // Levenberg-Marquardt iterations performed
  bool aborted = false;      // stopped by the abort flag
  double initialCost = 0.0;  // Ceres cost (robustified, 0.5 sum rho) before / after
  double finalCost = 0.0;
};

// Throws lumaslam::Error for inconsistent input (duplicate ids, an observation of an unknown
// keyframe/point, non-positive focal length or invSigma2, stereo observations without bf).
LocalBAResult optimizeLocalBundle(const LocalBAProblem& problem,
                                  const LocalBAOptions& options = {});

}  // namespace lumaslam::optimize
