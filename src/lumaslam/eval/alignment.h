#pragma once
// Alignment of an estimated trajectory onto ground truth with Umeyama's method (1991):
// the similarity (s, R, t) minimising sum |p_gt - (s R p_est + t)|^2 over matched positions.
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "lumaslam/core/pose.h"

namespace lumaslam::eval {

enum class AlignMode {
  None,  // compare in the estimate's own frame
  SE3,   // rotation + translation (stereo, RGB-D, inertial)
  Sim3,  // rotation + translation + scale (monocular)
};

// "none", "se3", "sim3"; throws Error naming the value otherwise.
AlignMode parseAlignMode(std::string_view name);
std::string toString(AlignMode mode);

struct Alignment {
  AlignMode mode = AlignMode::None;
  double scale = 1.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return scale * R * p + t; }
  // The pose moved into the ground-truth frame: rotation R R_w_c, position s R p + t
  // (as evo's Sim(3) alignment: scale changes positions, not orientations).
  SE3 apply(const SE3& T_w_c) const;
  Trajectory apply(const Trajectory& trajectory) const;
};

// `estimate` and `ground_truth` are associated pose for pose (same size). Needs at least
// 3 pairs for SE3/Sim3 and, for Sim3, an estimate that moves; throws Error otherwise.
Alignment align(const Trajectory& estimate, const Trajectory& ground_truth, AlignMode mode);

}  // namespace lumaslam::eval
