#pragma once
// The similarity between two keyframes from matched map points, robust to wrong matches
// (ORB-SLAM's Sim3Solver for monocular loops): RANSAC over minimal sets of 3 pairs, each
// solved in closed form by Umeyama's method with scale (Eigen::umeyama); a hypothesis' inliers
// reproject into both images within the chi-square threshold; the best set is solved again
// from all its inliers.
#include <optional>
#include <vector>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/optimize/sim3.h"
#include "lumaslam/optimize/sim3_alignment.h"

namespace lumaslam::loop {

struct Sim3RansacParams {
  int iterations = 300;
  int min_inliers = 20;  // ORB-SLAM: 20
  double chi2 = 9.210;   // per image, times the keypoint's invSigma2 (ORB-SLAM: 9.21)
  unsigned seed = 0;     // the sampling is deterministic for a given seed
};

struct Sim3RansacResult {
  optimize::Sim3 S_12{};
  std::vector<bool> inlier{};  // per pair
  int inliers = 0;
};

// nullopt when fewer than min_inliers pairs agree on one similarity.
std::optional<Sim3RansacResult> estimateSim3Ransac(const std::vector<optimize::Sim3Pair>& pairs,
                                                   const CameraIntrinsics& camera,
                                                   const Sim3RansacParams& params = {});

}  // namespace lumaslam::loop
