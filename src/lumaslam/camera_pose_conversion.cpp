#include "lumaslam/camera_pose_conversion.h"

#include <cmath>

#include "lumaslam/core/error.h"

namespace lumaslam {

namespace {

void checkRigid(const CameraPose& pose, std::size_t index) {
  const Eigen::Matrix4d& T = pose.T_w_c;
  if (!T.allFinite()) fail("pose {} (t={:.6f}): not finite", index, pose.timestamp);
  const Eigen::RowVector4d last_row(0, 0, 0, 1);
  if ((T.row(3) - last_row).cwiseAbs().maxCoeff() > 1e-9) {
    fail("pose {} (t={:.6f}): last row is not (0 0 0 1)", index, pose.timestamp);
  }
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > 1e-6 || R.determinant() < 0) {
    fail("pose {} (t={:.6f}): rotation is not orthonormal (|RᵀR - I| = {:.2g})", index,
         pose.timestamp, off);
  }
}

}  // namespace

Trajectory toTrajectory(const CameraTrajectory& trajectory) {
  Trajectory out;
  out.reserve(trajectory.size());
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    checkRigid(trajectory[i], i);
    StampedPose pose;
    pose.timestamp = trajectory[i].timestamp;
    pose.T_w_c.matrix() = trajectory[i].T_w_c;
    out.push_back(pose);
  }
  return out;
}

}  // namespace lumaslam
