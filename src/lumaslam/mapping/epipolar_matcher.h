#pragma once
// Matches between the features of two keyframes that have no map point yet, constrained by
// the epipolar geometry (ORB-SLAM's SearchForTriangulation, with a brute-force candidate scan
// instead of a vocabulary: keyframes hold ~1000 features, most already have points).
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/map/keyframe.h"

namespace lumaslam::mapping {

std::vector<std::pair<std::size_t, std::size_t>> matchForTriangulation(const map::KeyFrame& kf1,
                                                                       const map::KeyFrame& kf2,
                                                                       const Eigen::Matrix3d& F21);

}  // namespace lumaslam::mapping
