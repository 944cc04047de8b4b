#pragma once
// Ceres cost functions with analytic Jacobians for the reprojection error (reprojection_error.h)
// whitened by the keypoint's pyramid level: r = sqrt(invSigma2) * e.
//  - PoseReprojectionCost<N>: pose-only optimisation, the world point is a constant.
//  - BundleReprojectionCost<N>: bundle adjustment, pose and point are both parameters.
// Pose blocks use the layout and "lifted" Jacobian convention of se3_parameter.h.
// A disabled cost (an observation excluded as an outlier in this round) returns zeros, which
// keeps one ceres::Problem alive across the rounds instead of rebuilding it.
#include <algorithm>
#include <cmath>

#include <ceres/sized_cost_function.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lumaslam/optimize/reprojection_error.h"
#include "lumaslam/optimize/se3_parameter.h"

namespace lumaslam::optimize {

namespace detail {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

// Evaluates r = w e(R X + t) and, if asked, the lifted pose Jacobian and the point Jacobian.
template <int N>
bool evaluateReprojection(const CameraIntrinsics& camera, const Measurement<N>& measured,
                          double sqrtInfo, const double* pose, const Eigen::Vector3d& X_w,
                          double* residuals, double* poseJacobian, double* pointJacobian) {
  const Eigen::Map<const Eigen::Quaterniond> q(pose);
  const Eigen::Map<const Eigen::Vector3d> t(pose + 4);
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  const Eigen::Vector3d P_c = R * X_w + t;
  Measurement<N> error;
  Eigen::Matrix<double, N, 3> dError_dPc;
  const bool wantJacobian = poseJacobian != nullptr || pointJacobian != nullptr;
  if (!reprojectionError<N>(camera, P_c, measured, error, wantJacobian ? &dError_dPc : nullptr))
    return false;
  Eigen::Map<Measurement<N>> residualMap(residuals);
  residualMap = sqrtInfo * error;
  if (poseJacobian) {
    // dP_c/d(omega, upsilon) = [-[P_c]x | I] (se3_parameter.h).
    Eigen::Map<Eigen::Matrix<double, N, kPoseBlockSize, Eigen::RowMajor>> J(poseJacobian);
    J.template leftCols<3>() = -sqrtInfo * dError_dPc * skew(P_c);
    J.template middleCols<3>(3) = sqrtInfo * dError_dPc;
    J.col(6).setZero();
  }
  if (pointJacobian) {
    Eigen::Map<Eigen::Matrix<double, N, 3, Eigen::RowMajor>> J(pointJacobian);
    J = sqrtInfo * dError_dPc * R;
  }
  return true;
}

template <int N>
void zeroOutputs(int parameterSizes0, int parameterSizes1, double* residuals, double** jacobians) {
  std::fill(residuals, residuals + N, 0.0);
  if (!jacobians) return;
  if (jacobians[0]) std::fill(jacobians[0], jacobians[0] + N * parameterSizes0, 0.0);
  if (parameterSizes1 > 0 && jacobians[1])
    std::fill(jacobians[1], jacobians[1] + N * parameterSizes1, 0.0);
}

}  // namespace detail

template <int N>
class PoseReprojectionCost final : public ceres::SizedCostFunction<N, kPoseBlockSize> {
 public:
  PoseReprojectionCost(const CameraIntrinsics& camera, const Eigen::Vector3d& X_w,
                       const Measurement<N>& measured, double invSigma2)
      : camera_(camera), X_w_(X_w), measured_(measured), sqrtInfo_(std::sqrt(invSigma2)) {}

  void setEnabled(bool enabled) { enabled_ = enabled; }

  bool Evaluate(const double* const* parameters, double* residuals,
                double** jacobians) const override {
    if (!enabled_) {
      detail::zeroOutputs<N>(kPoseBlockSize, 0, residuals, jacobians);
      return true;
    }
    return detail::evaluateReprojection<N>(camera_, measured_, sqrtInfo_, parameters[0], X_w_,
                                           residuals, jacobians ? jacobians[0] : nullptr, nullptr);
  }

 private:
  CameraIntrinsics camera_;
  Eigen::Vector3d X_w_;
  Measurement<N> measured_;
  double sqrtInfo_;
  bool enabled_ = true;
};

template <int N>
class BundleReprojectionCost final : public ceres::SizedCostFunction<N, kPoseBlockSize, 3> {
 public:
  BundleReprojectionCost(const CameraIntrinsics& camera, const Measurement<N>& measured,
                         double invSigma2)
      : camera_(camera), measured_(measured), sqrtInfo_(std::sqrt(invSigma2)) {}

  void setEnabled(bool enabled) { enabled_ = enabled; }

  bool Evaluate(const double* const* parameters, double* residuals,
                double** jacobians) const override {
    if (!enabled_) {
      detail::zeroOutputs<N>(kPoseBlockSize, 3, residuals, jacobians);
      return true;
    }
    const Eigen::Map<const Eigen::Vector3d> X_w(parameters[1]);
    return detail::evaluateReprojection<N>(camera_, measured_, sqrtInfo_, parameters[0], X_w,
                                           residuals, jacobians ? jacobians[0] : nullptr,
                                           jacobians ? jacobians[1] : nullptr);
  }

 private:
  CameraIntrinsics camera_;
  Measurement<N> measured_;
  double sqrtInfo_;
  bool enabled_ = true;
};

}  // namespace lumaslam::optimize
