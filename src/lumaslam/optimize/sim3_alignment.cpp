#include "lumaslam/optimize/sim3_alignment.h"

#include <array>
#include <cmath>

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

namespace lumaslam::optimize {

namespace {

template <typename T>
Eigen::Matrix<T, 2, 1> project(const CameraIntrinsics& camera, const Eigen::Matrix<T, 3, 1>& X) {
  return {T(camera.fx) * X.x() / X.z() + T(camera.cx), T(camera.fy) * X.y() / X.z() + T(camera.cy)};
}

// Both reprojections of one pair, each scaled by sqrt(invSigma2).
struct PairError {
  PairError(const Sim3Pair& pair, const CameraIntrinsics& camera1, const CameraIntrinsics& camera2)
      : pair(pair), camera1(camera1), camera2(camera2) {}

  template <typename T>
  bool operator()(const T* q, const T* t, const T* logScale, T* residual) const {
    using Vector3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(q);
    const Eigen::Map<const Vector3> translation(t);
    using std::exp;
    const T scale = exp(*logScale);
    // S_12 X2 = s R X2 + t;  S_12^-1 X1 = R^T (X1 - t) / s.
    const Vector3 X2_in_1 = scale * (rotation * pair.X2.cast<T>()) + translation;
    const Vector3 X1_in_2 = (rotation.conjugate() * (pair.X1.cast<T>() - translation)) / scale;
    const Eigen::Matrix<T, 2, 1> e1 = pair.uv1.cast<T>() - project(camera1, X2_in_1);
    const Eigen::Matrix<T, 2, 1> e2 = pair.uv2.cast<T>() - project(camera2, X1_in_2);
    const T w1(std::sqrt(pair.invSigma2_1));
    const T w2(std::sqrt(pair.invSigma2_2));
    residual[0] = w1 * e1.x();
    residual[1] = w1 * e1.y();
    residual[2] = w2 * e2.x();
    residual[3] = w2 * e2.y();
    return true;
  }

  Sim3Pair pair;
  CameraIntrinsics camera1;
  CameraIntrinsics camera2;
};

}  // namespace

Eigen::Vector2d sim3PairChi2(const Sim3& S_12, const Sim3Pair& pair,
                             const CameraIntrinsics& camera1, const CameraIntrinsics& camera2) {
  const Eigen::Vector3d X2_in_1 = S_12 * pair.X2;
  const Eigen::Vector3d X1_in_2 = S_12.inverse() * pair.X1;
  constexpr double kBehind = 1e12;
  const double chi1 = X2_in_1.z() > 0.0
                          ? (pair.uv1 - project(camera1, X2_in_1)).squaredNorm() * pair.invSigma2_1
                          : kBehind;
  const double chi2 = X1_in_2.z() > 0.0
                          ? (pair.uv2 - project(camera2, X1_in_2)).squaredNorm() * pair.invSigma2_2
                          : kBehind;
  return {chi1, chi2};
}

Sim3AlignmentResult refineSim3(const std::vector<Sim3Pair>& pairs, const Sim3& initial,
                               const CameraIntrinsics& camera,
                               const Sim3AlignmentOptions& options) {
  const CameraIntrinsics& camera2 = options.camera2 ? *options.camera2 : camera;
  const Eigen::Quaterniond q0 = initial.rotation.normalized();
  std::array<double, 4> q{q0.x(), q0.y(), q0.z(), q0.w()};
  std::array<double, 3> t{initial.translation.x(), initial.translation.y(),
                          initial.translation.z()};
  double logScale = std::log(initial.scale);
  const auto current = [&] {
    return Sim3{std::exp(logScale), Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized(),
                Eigen::Vector3d(t[0], t[1], t[2])};
  };

  Sim3AlignmentResult result;
  result.inlier.assign(pairs.size(), true);
  ceres::EigenQuaternionManifold quaternionManifold;
  for (int round = 0; round < 2; ++round) {
    ceres::Problem::Options problemOptions;
    problemOptions.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problemOptions);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      if (!result.inlier[p]) continue;
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PairError, 4, 4, 3, 1>(
                                   new PairError(pairs[p], camera, camera2)),
                               new ceres::HuberLoss(std::sqrt(options.chi2)), q.data(), t.data(),
                               &logScale);
    }
    if (problem.NumResidualBlocks() == 0) break;
    problem.SetManifold(q.data(), &quaternionManifold);
    ceres::Solver::Options solverOptions;
    solverOptions.linear_solver_type = ceres::DENSE_QR;
    solverOptions.max_num_iterations = options.iterations;
    solverOptions.num_threads = 1;
    solverOptions.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solverOptions, &problem, &summary);
    const Sim3 S = current();
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      if (!result.inlier[p]) continue;
      const Eigen::Vector2d chi2 = sim3PairChi2(S, pairs[p], camera, camera2);
      if (chi2.x() > options.chi2 || chi2.y() > options.chi2) result.inlier[p] = false;
    }
  }
  result.S_12 = current();
  for (const bool in : result.inlier) result.inliers += in ? 1 : 0;
  return result;
}

}  // namespace lumaslam::optimize
