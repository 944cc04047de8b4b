#include "lumaslam/optimize/pose_levenberg_marquardt.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "lumaslam/optimize/reprojection_error.h"
#include "lumaslam/optimize/se3_parameter.h"

namespace lumaslam::optimize {

namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// Ceres' defaults (ceres::Solver::Options).
constexpr double kInitialRadius = 1e4;
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kMinRelativeDecrease = 1e-3;
constexpr double kFunctionTolerance = 1e-6;
constexpr double kGradientTolerance = 1e-10;
constexpr double kParameterTolerance = 1e-8;

// Huber rho(s) on the squared whitened norm s and its derivative rho'(s).
struct Robust {
  double rho, weight;
};
Robust huber(double s, double delta) {
  if (delta <= 0.0 || s <= delta * delta) return {s, 1.0};
  const double norm = std::sqrt(s);
  return {2.0 * delta * norm - delta * delta, delta / norm};
}

struct Linearisation {
  double cost = 0.0;  // 1/2 sum rho, as Ceres reports it
  Matrix6 H = Matrix6::Zero();
  Vector6 g = Vector6::Zero();  // gradient of the cost
};

template <int N>
bool accumulate(const CameraIntrinsics& camera, const Eigen::Vector3d& P_c,
                const Eigen::Vector3d& measured, double sqrtInfo, double delta, Linearisation& out,
                bool withJacobian) {
  Measurement<N> error;
  Eigen::Matrix<double, N, 3> dError_dPc;
  if (!reprojectionError<N>(camera, P_c, measured.head<N>(), error,
                            withJacobian ? &dError_dPc : nullptr))
    return false;
  const Measurement<N> r = sqrtInfo * error;
  const Robust robust = huber(r.squaredNorm(), delta);
  out.cost += 0.5 * robust.rho;
  if (!withJacobian) return true;
  // dP_c / d(omega, upsilon) = [-[P_c]x | I] at delta = 0 (se3_parameter.h).
  Eigen::Matrix<double, N, 6> J;
  const Eigen::Matrix<double, N, 3> A = sqrtInfo * dError_dPc;
  Eigen::Matrix3d minusSkew;
  minusSkew << 0.0, P_c.z(), -P_c.y(), -P_c.z(), 0.0, P_c.x(), P_c.y(), -P_c.x(), 0.0;
  J.template leftCols<3>() = A * minusSkew;
  J.template rightCols<3>() = A;
  // Fixed-size products (Eigen unrolls them); a selfadjoint rankUpdate took the generic
  // triangular-product path, 85% of this function's instructions.
  const Eigen::Matrix<double, 6, N> weightedTranspose = robust.weight * J.transpose();
  out.H.noalias() += weightedTranspose.lazyProduct(J);
  out.g.noalias() += weightedTranspose * r;
  return true;
}

// Cost (and, if asked, H and g) at T; false if an active point is not in front of T.
bool linearise(const CameraIntrinsics& camera, const std::vector<PoseObservation>& observations,
               const std::vector<char>& active, const SE3& T, double deltaMono, double deltaStereo,
               bool withJacobian, Linearisation& out) {
  out = Linearisation{};
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d t = T.translation();
  for (std::size_t i = 0; i < observations.size(); ++i) {
    if (!active[i]) continue;
    const PoseObservation& obs = observations[i];
    const Eigen::Vector3d P_c = R * obs.X_w + t;
    const double sqrtInfo = std::sqrt(obs.invSigma2);
    const bool ok = obs.isStereo()
                        ? accumulate<3>(camera, P_c, {obs.uv.x(), obs.uv.y(), obs.uRight}, sqrtInfo,
                                        deltaStereo, out, withJacobian)
                        : accumulate<2>(camera, P_c, {obs.uv.x(), obs.uv.y(), 0.0}, sqrtInfo,
                                        deltaMono, out, withJacobian);
    if (!ok) return false;
  }
  return true;
}

// The rotation goes through a normalised quaternion: a product of rotation matrices drifts
// off orthonormality, and the tracker's motion model (T_c_w * T_last^-1 with the transpose as
// inverse) amplified that drift from 1e-16 to a broken pose within ~40 frames.
SE3 applyUpdate(const Vector6& delta, const SE3& T) {
  const Eigen::Quaterniond step = expSO3(delta.head<3>());
  SE3 updated = SE3::Identity();
  updated.linear() = (step * Eigen::Quaterniond(T.linear())).normalized().toRotationMatrix();
  updated.translation() = step * T.translation() + delta.tail<3>();
  return updated;
}

}  // namespace

PoseRoundResult minimizePoseLevenbergMarquardt(const CameraIntrinsics& camera,
                                               const std::vector<PoseObservation>& observations,
                                               const std::vector<char>& active, const SE3& T_c_w,
                                               double huberDeltaMono, double huberDeltaStereo,
                                               int maxIterations) {
  PoseRoundResult result;
  result.T_c_w = T_c_w;
  Linearisation current;
  if (!linearise(camera, observations, active, T_c_w, huberDeltaMono, huberDeltaStereo, true,
                 current))
    return result;
  double radius = kInitialRadius;
  double decreaseFactor = 2.0;
  // |x| of Ceres' parameter tolerance: the 7-double block (unit quaternion, translation).
  const auto blockNorm = [](const SE3& T) {
    return std::sqrt(1.0 + T.translation().squaredNorm());
  };
  while (result.iterations < maxIterations) {
    if (current.g.lpNorm<Eigen::Infinity>() <= kGradientTolerance) break;
    ++result.iterations;
    Matrix6 damped = current.H;
    damped.diagonal() +=
        current.H.diagonal().cwiseMax(kMinDiagonal).cwiseMin(kMaxDiagonal) / radius;
    const Vector6 step = damped.ldlt().solve(-current.g);
    const double modelDecrease = -(current.g.dot(step) + 0.5 * step.dot(current.H * step));
    if (step.norm() <= kParameterTolerance * (blockNorm(result.T_c_w) + kParameterTolerance)) break;

    const SE3 candidate = applyUpdate(step, result.T_c_w);
    Linearisation trial;
    const bool valid = step.allFinite() && modelDecrease > 0.0 &&
                       linearise(camera, observations, active, candidate, huberDeltaMono,
                                 huberDeltaStereo, false, trial);
    if (valid) {
      const double costChange = current.cost - trial.cost;
      if (std::abs(costChange) <= kFunctionTolerance * current.cost) {
        if (costChange > 0.0) result.T_c_w = candidate;
        break;
      }
      const double quality = costChange / modelDecrease;
      if (quality > kMinRelativeDecrease) {
        result.T_c_w = candidate;
        linearise(camera, observations, active, candidate, huberDeltaMono, huberDeltaStereo, true,
                  current);
        radius = std::min(kMaxRadius,
                          radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * quality - 1.0, 3)));
        decreaseFactor = 2.0;
        continue;
      }
    }
    radius /= decreaseFactor;
    decreaseFactor *= 2.0;
    if (radius < kMinRadius) break;
  }
  return result;
}

}  // namespace lumaslam::optimize
