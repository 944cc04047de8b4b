#include "lumaslam/mapping/triangulation.h"

#include <Eigen/SVD>

namespace lumaslam::mapping {

std::optional<Eigen::Vector3d> triangulateLinear(const Eigen::Vector2d& x1, const SE3& T_c1_w,
                                                 const Eigen::Vector2d& x2, const SE3& T_c2_w) {
  const Eigen::Matrix<double, 3, 4> P1 = T_c1_w.matrix().topRows<3>();
  const Eigen::Matrix<double, 3, 4> P2 = T_c2_w.matrix().topRows<3>();
  Eigen::Matrix4d A;
  A.row(0) = x1.x() * P1.row(2) - P1.row(0);
  A.row(1) = x1.y() * P1.row(2) - P1.row(1);
  A.row(2) = x2.x() * P2.row(2) - P2.row(0);
  A.row(3) = x2.y() * P2.row(2) - P2.row(1);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X.w()) < 1e-12) return std::nullopt;
  return Eigen::Vector3d(X.head<3>() / X.w());
}

Eigen::Matrix3d fundamental21(const SE3& T_c1_w, const SE3& T_c2_w, const CameraIntrinsics& k) {
  const SE3 T_21 = T_c2_w * T_c1_w.inverse();
  const Eigen::Matrix3d R = T_21.rotation();
  const Eigen::Vector3d t = T_21.translation();
  Eigen::Matrix3d t_hat;
  t_hat << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  Eigen::Matrix3d K;
  K << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1;
  const Eigen::Matrix3d K_inv = K.inverse();
  return K_inv.transpose() * t_hat * R * K_inv;
}

double epipolarDistance2(const Eigen::Matrix3d& F21, const Eigen::Vector2d& p1,
                         const Eigen::Vector2d& p2) {
  const Eigen::Vector3d line = F21 * p1.homogeneous();
  const double num = line.dot(p2.homogeneous());
  const double den = line.x() * line.x() + line.y() * line.y();
  return den > 0 ? num * num / den : std::numeric_limits<double>::infinity();
}

bool reprojectionAcceptable(const Eigen::Vector3d& X_w, const SE3& T_c_w, const CameraIntrinsics& k,
                            const Eigen::Vector2d& uv, double u_right, double sigma2) {
  const Eigen::Vector3d X_c = T_c_w * X_w;
  if (X_c.z() <= 0) return false;
  const double inv_z = 1.0 / X_c.z();
  const double u = k.fx * X_c.x() * inv_z + k.cx;
  const double v = k.fy * X_c.y() * inv_z + k.cy;
  double error2 = (u - uv.x()) * (u - uv.x()) + (v - uv.y()) * (v - uv.y());
  if (u_right < 0) return error2 < 5.991 * sigma2;
  const double ur = u - k.bf * inv_z;
  error2 += (ur - u_right) * (ur - u_right);
  return error2 < 7.815 * sigma2;
}

}  // namespace lumaslam::mapping
