#include "lumaslam/optimize/pose_batch_cost.h"

#include <cmath>

#include <Eigen/Geometry>

#include "lumaslam/optimize/reprojection_error.h"
#include "lumaslam/optimize/se3_parameter.h"

namespace lumaslam::optimize {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

// Whitened residual rows r (N x 1) and, optionally, their tangent Jacobian (N x 6), robustified
// in place as described in the header.
// SO(3) left Jacobian: d(Exp(omega) p)/d omega = -[Exp(omega) p]x J_l(omega).
Eigen::Matrix3d leftJacobianSO3(const Eigen::Vector3d& omega) {
  const double theta2 = omega.squaredNorm();
  const Eigen::Matrix3d W = skew(omega);
  if (theta2 < 1e-10) return Eigen::Matrix3d::Identity() + 0.5 * W + W * W / 6.0;
  const double theta = std::sqrt(theta2);
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / theta2 * W +
         (theta - std::sin(theta)) / (theta2 * theta) * W * W;
}

// The current pose T(delta) and what the per-row Jacobian needs from delta.
struct PoseAtDelta {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  Eigen::Vector3d upsilon;
  Eigen::Matrix3d leftJacobian;
};

template <int N>
bool evaluateObservation(const CameraIntrinsics& camera, const PoseAtDelta& pose,
                         const Eigen::Vector3d& X_w, const Eigen::Vector3d& measured,
                         double sqrtInfo, double huberDelta, Eigen::Matrix<double, N, 1>& r,
                         Eigen::Matrix<double, N, 6>* J) {
  const Eigen::Vector3d P_c = pose.R * X_w + pose.t;
  Measurement<N> error;
  Eigen::Matrix<double, N, 3> dError_dPc;
  if (!reprojectionError<N>(camera, P_c, measured.head<N>(), error, J ? &dError_dPc : nullptr))
    return false;
  r = sqrtInfo * error;
  if (J) {
    // P_c = Exp(omega) (R0 X + t0) + upsilon.
    J->template leftCols<3>() =
        -sqrtInfo * dError_dPc * skew(P_c - pose.upsilon) * pose.leftJacobian;
    J->template rightCols<3>() = sqrtInfo * dError_dPc;
  }
  const double s = r.squaredNorm();
  if (huberDelta > 0.0 && s > huberDelta * huberDelta) {
    // rho(s) = 2 delta sqrt(s) - delta^2; g^2 = rho / s; d(g^2)/ds = -delta s^-3/2 + delta^2 s^-2.
    const double sqrtS = std::sqrt(s);
    const double g = std::sqrt((2.0 * huberDelta * sqrtS - huberDelta * huberDelta) / s);
    if (J) {
      const double dg2_ds = (-huberDelta / sqrtS + huberDelta * huberDelta / s) / s;
      const double twoDg_ds = dg2_ds / g;  // 2 g' = (g^2)' / g
      *J = (g * Eigen::Matrix<double, N, N>::Identity() + twoDg_ds * r * r.transpose()) * *J;
    }
    r *= g;
  }
  return true;
}

}  // namespace

PoseBatchCost::PoseBatchCost(const CameraIntrinsics& camera,
                             const std::vector<PoseObservation>& observations, const SE3& reference)
    : camera_(camera), reference_(reference), active_(observations.size(), 1) {
  int rows = 0;
  entries_.reserve(observations.size());
  for (const PoseObservation& obs : observations) {
    const bool stereo = obs.isStereo();
    entries_.push_back({obs.X_w, Eigen::Vector3d(obs.uv.x(), obs.uv.y(), stereo ? obs.uRight : 0.0),
                        std::sqrt(obs.invSigma2), rows, stereo});
    rows += stereo ? 3 : 2;
  }
  set_num_residuals(rows);
  mutable_parameter_block_sizes()->push_back(kParameters);
}

SE3 PoseBatchCost::poseAt(const double* delta) const {
  // Through a normalised quaternion: a product of rotation matrices drifts off orthonormality,
  // which the tracker's motion model amplifies (see pose_levenberg_marquardt.cpp).
  const Eigen::Quaterniond step = expSO3(Eigen::Map<const Eigen::Vector3d>(delta));
  SE3 pose = SE3::Identity();
  pose.linear() = (step * Eigen::Quaterniond(reference_.linear())).normalized().toRotationMatrix();
  pose.translation() =
      step * reference_.translation() + Eigen::Map<const Eigen::Vector3d>(delta + 3);
  return pose;
}

void PoseBatchCost::setHuberDeltas(double mono, double stereo) {
  huberMono_ = mono;
  huberStereo_ = stereo;
}

bool PoseBatchCost::Evaluate(const double* const* parameters, double* residuals,
                             double** jacobians) const {
  const double* delta = parameters[0];
  const SE3 T = poseAt(delta);
  const Eigen::Vector3d omega(delta[0], delta[1], delta[2]);
  double* jacobian = jacobians ? jacobians[0] : nullptr;
  const PoseAtDelta pose{T.linear(), T.translation(), Eigen::Vector3d(delta[3], delta[4], delta[5]),
                         jacobian ? leftJacobianSO3(omega) : Eigen::Matrix3d::Identity()};
  using JacobianRows =
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, kParameters, Eigen::RowMajor>>;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    const int n = e.stereo ? 3 : 2;
    if (!active_[i]) {
      for (int k = 0; k < n; ++k) residuals[e.row + k] = 0.0;
      if (jacobian) JacobianRows(jacobian + e.row * kParameters, n, kParameters).setZero();
      continue;
    }
    if (e.stereo) {
      Eigen::Matrix<double, 3, 1> r;
      Eigen::Matrix<double, 3, 6> J;
      if (!evaluateObservation<3>(camera_, pose, e.X_w, e.measured, e.sqrtInfo, huberStereo_, r,
                                  jacobian ? &J : nullptr))
        return false;
      Eigen::Map<Eigen::Vector3d>(residuals + e.row, 3) = r;
      if (jacobian) {
        JacobianRows(jacobian + e.row * kParameters, 3, kParameters) = J;
      }
    } else {
      Eigen::Matrix<double, 2, 1> r;
      Eigen::Matrix<double, 2, 6> J;
      if (!evaluateObservation<2>(camera_, pose, e.X_w, e.measured, e.sqrtInfo, huberMono_, r,
                                  jacobian ? &J : nullptr))
        return false;
      residuals[e.row] = r(0);
      residuals[e.row + 1] = r(1);
      if (jacobian) {
        JacobianRows(jacobian + e.row * kParameters, 2, kParameters) = J;
      }
    }
  }
  return true;
}

}  // namespace lumaslam::optimize
