#pragma once
// Between the public CameraTrajectory (camera_pose.h) and the internal Trajectory
// (core/pose.h). Internal: not installed.
#include "lumaslam/camera_pose.h"
#include "lumaslam/core/pose.h"

namespace lumaslam {

inline CameraTrajectory toCameraTrajectory(const Trajectory& trajectory) {
  CameraTrajectory out;
  out.reserve(trajectory.size());
  for (const auto& pose : trajectory) out.push_back({pose.timestamp, pose.T_w_c.matrix()});
  return out;
}

// Throws Error when a pose's last row is not (0 0 0 1) or its rotation is not orthonormal.
Trajectory toTrajectory(const CameraTrajectory& trajectory);

}  // namespace lumaslam
