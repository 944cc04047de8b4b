#pragma once
// Every observation of a pose-only problem in ONE Ceres residual block. Measured: Ceres spends
// ~100 ns of bookkeeping per residual block and evaluation (loss corrector, manifold product,
// Jacobian scatter), several times the reprojection itself, so one block per observation made
// pose-only optimisation ~3x slower (docs/optimization.md).
//
// Each observation's Huber kernel is therefore applied inside: its whitened residual r
// (s = |r|^2) is replaced by r' = g(s) r with g = sqrt(rho(s) / s), so |r'|^2 = rho(s) and the
// objective is exactly sum_i rho(s_i); the Jacobian is the exact derivative of r',
// (g I + 2 g'(s) r r^T) J. Inside the Huber threshold g = 1 and r' = r.
// Parameterisation: the block is a plain 6-vector delta = (omega, upsilon) applied to a
// reference pose T0 as in se3_parameter.h, T(delta) = [Exp(omega) | upsilon] * T0, with the
// exact Jacobian (SO(3) left Jacobian J_l(omega)), so no ceres::Manifold is involved: Ceres'
// manifold product over all rows doubled the Jacobian evaluation time. The optimiser moves
// the reference to the current estimate between rounds so delta stays small.
#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "lumaslam/core/camera_intrinsics.h"
#include "lumaslam/core/pose.h"
#include "lumaslam/optimize/pose_only.h"

namespace lumaslam::optimize {

class PoseBatchCost final : public ceres::CostFunction {
 public:
  static constexpr int kParameters = 6;

  PoseBatchCost(const CameraIntrinsics& camera, const std::vector<PoseObservation>& observations,
                const SE3& reference);

  void setReference(const SE3& reference) { reference_ = reference; }
  const SE3& reference() const { return reference_; }
  // T(delta) = [Exp(omega) | upsilon] * reference.
  SE3 poseAt(const double* delta) const;

  // Huber deltas on the whitened residual norm; 0 disables the kernel (plain least squares).
  void setHuberDeltas(double mono, double stereo);
  // An inactive observation contributes zero rows (excluded outlier).
  void setActive(int observation, bool active) { active_[observation] = active; }

  bool Evaluate(const double* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  struct Entry {
    Eigen::Vector3d X_w;
    Eigen::Vector3d measured;  // u, v[, u_r]
    double sqrtInfo;
    int row;  // first residual row
    bool stereo;
  };
  CameraIntrinsics camera_;
  SE3 reference_;
  std::vector<Entry> entries_;
  std::vector<char> active_;
  double huberMono_ = 0.0;
  double huberStereo_ = 0.0;
};

}  // namespace lumaslam::optimize
