#pragma once
// How a pose lives in a Ceres parameter block, and its manifold.
//
// Block layout (7 doubles): quaternion (x, y, z, w; Eigen's storage order), then translation.
// Tangent (6 doubles): delta = (omega, upsilon), a left update applied to T_c_w:
//   T' = [Exp(omega) | upsilon] * T,   i.e. R' = Exp(omega) R,  t' = Exp(omega) t + upsilon.
// At delta = 0 this moves a camera point P_c = R X + t by dP_c = -[P_c]x omega + upsilon, the
// same first-order model as g2o's SE3Quat used by ORB-SLAM.
//
// Jacobian convention (the "lifted" Jacobian used e.g. by VINS-Mono/OKVIS): cost functions on
// this block write d(residual)/d(delta) into the first 6 columns of their 7-column Jacobian and
// zero in the last; the manifold's PlusJacobian is [I6; 0], so Ceres' product J * PlusJacobian
// is exactly the tangent Jacobian, without differentiating through the quaternion.
// Consequence: ceres::GradientChecker cannot check these blocks (it differentiates the ambient
// quaternion numerically); tests compare against automatic differentiation of
// residual(Plus(T, delta)) in delta instead.
#include <array>

#include <ceres/manifold.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lumaslam/core/pose.h"

namespace lumaslam::optimize {

inline constexpr int kPoseBlockSize = 7;
inline constexpr int kPoseTangentSize = 6;
using PoseBlock = std::array<double, kPoseBlockSize>;

PoseBlock toPoseBlock(const SE3& T);
SE3 fromPoseBlock(const double* block);

// Unit quaternion of the rotation vector omega (exact for any angle).
Eigen::Quaterniond expSO3(const Eigen::Vector3d& omega);
// Rotation vector of a unit quaternion, |omega| <= pi.
Eigen::Vector3d logSO3(const Eigen::Quaterniond& q);

class SE3LeftManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseBlockSize; }
  int TangentSize() const override { return kPoseTangentSize; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

// One stateless instance to hand to ceres::Problem (with manifold ownership DO_NOT_TAKE).
SE3LeftManifold* se3LeftManifold();

}  // namespace lumaslam::optimize
