#pragma once
// Two-view geometry for new map points: linear (DLT) triangulation and the checks ORB-SLAM's
// CreateNewMapPoints applies to a candidate (depth, reprojection chi-square, scale).
#include <optional>

#include <Eigen/Core>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/map/feature_set.h"

namespace lumaslam::mapping {

// Point seen at normalised image coordinates x1 (camera 1) and x2 (camera 2).
std::optional<Eigen::Vector3d> triangulateLinear(const Eigen::Vector2d& x1, const SE3& T_c1_w,
                                                 const Eigen::Vector2d& x2, const SE3& T_c2_w);

// Fundamental matrix mapping points of view 1 to epipolar lines in view 2 (l2 = F21 x1).
Eigen::Matrix3d fundamental21(const SE3& T_c1_w, const SE3& T_c2_w, const CameraIntrinsics& k);

// Squared distance of pixel p2 to the epipolar line of pixel p1.
double epipolarDistance2(const Eigen::Matrix3d& F21, const Eigen::Vector2d& p1,
                         const Eigen::Vector2d& p2);

// Chi-square reprojection test of X_w in a view: mono (u, v) at 5.991 or stereo (u, v, u_r)
// at 7.815, with the keypoint's level variance sigma2.
bool reprojectionAcceptable(const Eigen::Vector3d& X_w, const SE3& T_c_w, const CameraIntrinsics& k,
                            const Eigen::Vector2d& uv, double u_right, double sigma2);

}  // namespace lumaslam::mapping
