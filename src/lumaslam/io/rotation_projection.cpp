#include "lumaslam/io/rotation_projection.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace lumaslam::io {

std::optional<Eigen::Matrix3d> projectToRotation(const Eigen::Matrix3d& R, double tolerance) {
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (!(error <= tolerance) || R.determinant() <= 0.0) return std::nullopt;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

}  // namespace lumaslam::io
