#pragma once
// Rotation matrices read from text (KITTI poses, EuRoC T_BS) carry rounding errors.
#include <optional>

#include <Eigen/Core>

namespace lumaslam::io {

// The nearest rotation (SVD projection onto SO(3)) when R is one up to |R^T R - I| <= tolerance
// and det > 0; nullopt otherwise.
std::optional<Eigen::Matrix3d> projectToRotation(const Eigen::Matrix3d& R, double tolerance);

}  // namespace lumaslam::io
