#include "lumaslam/optimize/se3_parameter.h"

#include <cmath>

namespace lumaslam::optimize {

PoseBlock toPoseBlock(const SE3& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d& t = T.translation();
  return {q.x(), q.y(), q.z(), q.w(), t.x(), t.y(), t.z()};
}

SE3 fromPoseBlock(const double* block) {
  const Eigen::Quaterniond q = Eigen::Map<const Eigen::Quaterniond>(block).normalized();
  SE3 T = SE3::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Eigen::Map<const Eigen::Vector3d>(block + 4);
  return T;
}

Eigen::Quaterniond expSO3(const Eigen::Vector3d& omega) {
  const double theta = omega.norm();
  if (theta < 1e-10) {
    // Taylor expansion; the quaternion is normalised below.
    return Eigen::Quaterniond(1.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z()).normalized();
  }
  return Eigen::Quaterniond(Eigen::AngleAxisd(theta, omega / theta));
}

Eigen::Vector3d logSO3(const Eigen::Quaterniond& q) {
  // Take the representative with w >= 0 so the angle is in [0, pi].
  const Eigen::Quaterniond qp = q.w() < 0.0 ? Eigen::Quaterniond(-q.coeffs()) : q;
  const double sinHalf = qp.vec().norm();
  if (sinHalf < 1e-10) return 2.0 * qp.vec() / qp.w();
  const double angle = 2.0 * std::atan2(sinHalf, qp.w());
  return angle / sinHalf * qp.vec();
}

bool SE3LeftManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Eigen::Map<const Eigen::Quaterniond> q(x);
  const Eigen::Map<const Eigen::Vector3d> t(x + 4);
  const Eigen::Map<const Eigen::Vector3d> omega(delta);
  const Eigen::Map<const Eigen::Vector3d> upsilon(delta + 3);
  const Eigen::Quaterniond dq = expSO3(omega);
  Eigen::Map<Eigen::Quaterniond> qOut(x_plus_delta);
  Eigen::Map<Eigen::Vector3d> tOut(x_plus_delta + 4);
  qOut = (dq * q).normalized();
  tOut = dq * t + upsilon;
  return true;
}

bool SE3LeftManifold::PlusJacobian(const double* /*x*/, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.topRows<6>().setIdentity();
  return true;
}

bool SE3LeftManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  // y = [Exp(omega) | upsilon] * x  =>  [Exp(omega) | upsilon] = y * x^-1.
  const Eigen::Map<const Eigen::Quaterniond> qy(y);
  const Eigen::Map<const Eigen::Quaterniond> qx(x);
  const Eigen::Map<const Eigen::Vector3d> ty(y + 4);
  const Eigen::Map<const Eigen::Vector3d> tx(x + 4);
  const Eigen::Quaterniond dq = qy * qx.conjugate();
  Eigen::Map<Eigen::Vector3d> omega(y_minus_x);
  Eigen::Map<Eigen::Vector3d> upsilon(y_minus_x + 3);
  omega = logSO3(dq);
  upsilon = ty - dq * tx;
  return true;
}

bool SE3LeftManifold::MinusJacobian(const double* /*x*/, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.leftCols<6>().setIdentity();
  return true;
}

SE3LeftManifold* se3LeftManifold() {
  static SE3LeftManifold manifold;
  return &manifold;
}

}  // namespace lumaslam::optimize
