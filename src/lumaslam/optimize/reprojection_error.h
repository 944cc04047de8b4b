#pragma once
// Reprojection error of a camera-frame point: e = project(P_c) - measured, with
// project(P_c) = (fx x/z + cx, fy y/z + cy[, fx x/z + cx - bf/z]) for N = 2 (mono) or
// N = 3 (stereo: the third row is the right image's column u_r).
#include <limits>

#include <Eigen/Core>

#include "lumaslam/core/camera_intrinsics.h"

namespace lumaslam::optimize {

// Points closer than this (or behind the camera) cannot be projected.
inline constexpr double kMinProjectionDepth = 1e-6;

template <int N>
using Measurement = Eigen::Matrix<double, N, 1>;

// Writes the error (and optionally d error / d P_c) and returns true, or returns false when
// P_c is not in front of the camera.
template <int N>
bool reprojectionError(const CameraIntrinsics& camera, const Eigen::Vector3d& P_c,
                       const Measurement<N>& measured, Measurement<N>& error,
                       Eigen::Matrix<double, N, 3>* dError_dPc = nullptr) {
  static_assert(N == 2 || N == 3, "mono (2) or stereo (3) observations only");
  if (!(P_c.z() > kMinProjectionDepth)) return false;
  const double invZ = 1.0 / P_c.z();
  const double x = P_c.x() * invZ;
  const double y = P_c.y() * invZ;
  const double u = camera.fx * x + camera.cx;
  error(0) = u - measured(0);
  error(1) = camera.fy * y + camera.cy - measured(1);
  if constexpr (N == 3) error(2) = u - camera.bf * invZ - measured(2);
  if (dError_dPc) {
    auto& J = *dError_dPc;
    J(0, 0) = camera.fx * invZ;
    J(0, 1) = 0.0;
    J(0, 2) = -camera.fx * x * invZ;
    J(1, 0) = 0.0;
    J(1, 1) = camera.fy * invZ;
    J(1, 2) = -camera.fy * y * invZ;
    if constexpr (N == 3) {
      J(2, 0) = J(0, 0);
      J(2, 1) = 0.0;
      J(2, 2) = J(0, 2) + camera.bf * invZ * invZ;
    }
  }
  return true;
}

// invSigma2 * |e|^2, the statistic compared with the chi-square thresholds; +infinity for a
// point that is not in front of the camera.
template <int N>
double reprojectionChi2(const CameraIntrinsics& camera, const Eigen::Vector3d& P_c,
                        const Measurement<N>& measured, double invSigma2) {
  Measurement<N> error;
  if (!reprojectionError<N>(camera, P_c, measured, error))
    return std::numeric_limits<double>::infinity();
  return invSigma2 * error.squaredNorm();
}

}  // namespace lumaslam::optimize
