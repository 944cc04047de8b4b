// Analytic Jacobians against Ceres' numeric differentiation: the per-observation costs through
// the SE3 manifold's Plus (se3_parameter.h explains why not ceres::GradientChecker there), the
// batched pose-only cost with ceres::GradientChecker; plus the manifold's invariants.
#include <random>

#include <ceres/gradient_checker.h>
#include <ceres/loss_function.h>
#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include "lumaslam/optimize/pose_batch_cost.h"
#include "lumaslam/optimize/reprojection_cost.h"
#include "lumaslam/optimize/se3_parameter.h"
#include "lumaslam/optimize/synthetic_problems.h"

namespace lumaslam::optimize {
namespace {

// residual(Plus(pose, delta), X + dX) with the analytic cost's own Evaluate.
template <int N>
struct PerturbedResidual {
  const BundleReprojectionCost<N>* cost;
  PoseBlock pose;
  Eigen::Vector3d X_w;
  bool operator()(const double* delta, const double* dX, double* residual) const {
    PoseBlock moved;
    se3LeftManifold()->Plus(pose.data(), delta, moved.data());
    const Eigen::Vector3d X = X_w + Eigen::Map<const Eigen::Vector3d>(dX);
    const double* parameters[] = {moved.data(), X.data()};
    return cost->Evaluate(parameters, residual, nullptr);
  }
};

template <int N>
void expectJacobiansMatchNumeric(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const CameraIntrinsics camera = syntheticCamera();
  const SE3 T_c_w = perturbPose(SE3::Identity(), 0.5, 40.0, seed);
  const Eigen::Vector3d P_c(unit(rng), 0.6 * unit(rng), 3.0 + unit(rng));
  const Eigen::Vector3d X_w = T_c_w.inverse() * P_c;
  Measurement<N> measured;
  measured.setConstant(200.0);
  measured(0) += 50 * unit(rng);
  const double invSigma2 = 1.0 / 1.44;
  const BundleReprojectionCost<N> cost(camera, measured, invSigma2);

  const PoseBlock pose = toPoseBlock(T_c_w);
  double residual[N];
  double poseJacobian[N * kPoseBlockSize];
  double pointJacobian[N * 3];
  const double* parameters[] = {pose.data(), X_w.data()};
  double* jacobians[] = {poseJacobian, pointJacobian};
  ASSERT_TRUE(cost.Evaluate(parameters, residual, jacobians));

  ceres::NumericDiffOptions numericOptions;
  numericOptions.relative_step_size = 1e-7;
  ceres::NumericDiffCostFunction<PerturbedResidual<N>, ceres::CENTRAL, N, 6, 3> numeric(
      new PerturbedResidual<N>{&cost, pose, X_w}, ceres::TAKE_OWNERSHIP, N, numericOptions);
  const double zeros[6] = {0, 0, 0, 0, 0, 0};
  double numericResidual[N];
  double numericPose[N * 6];
  double numericPoint[N * 3];
  const double* numericParameters[] = {zeros, zeros};
  double* numericJacobians[] = {numericPose, numericPoint};
  ASSERT_TRUE(numeric.Evaluate(numericParameters, numericResidual, numericJacobians));

  for (int r = 0; r < N; ++r) {
    EXPECT_NEAR(residual[r], numericResidual[r], 1e-9);
    for (int c = 0; c < 6; ++c) {
      const double expected = numericPose[r * 6 + c];
      EXPECT_NEAR(poseJacobian[r * kPoseBlockSize + c], expected, 1e-5 * (1.0 + std::abs(expected)))
          << "pose row " << r << " col " << c;
    }
    EXPECT_EQ(poseJacobian[r * kPoseBlockSize + 6], 0.0);
    for (int c = 0; c < 3; ++c) {
      const double expected = numericPoint[r * 3 + c];
      EXPECT_NEAR(pointJacobian[r * 3 + c], expected, 1e-5 * (1.0 + std::abs(expected)))
          << "point row " << r << " col " << c;
    }
  }

  // The pose-only cost must agree with the bundle cost's pose Jacobian.
  const PoseReprojectionCost<N> poseCost(camera, X_w, measured, invSigma2);
  double poseOnlyResidual[N];
  double poseOnlyJacobian[N * kPoseBlockSize];
  const double* poseParameters[] = {pose.data()};
  double* poseJacobians[] = {poseOnlyJacobian};
  ASSERT_TRUE(poseCost.Evaluate(poseParameters, poseOnlyResidual, poseJacobians));
  for (int i = 0; i < N * kPoseBlockSize; ++i)
    EXPECT_DOUBLE_EQ(poseOnlyJacobian[i], poseJacobian[i]);
}

TEST(OptimizeJacobians, MonoReprojectionMatchesNumericDiff) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) expectJacobiansMatchNumeric<2>(seed);
}

TEST(OptimizeJacobians, StereoReprojectionMatchesNumericDiff) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) expectJacobiansMatchNumeric<3>(seed);
}

// The batched pose-only cost has a plain 6-vector parameter (no manifold), so Ceres' own
// GradientChecker applies. Checked away from delta = 0 (the SO(3) left Jacobian matters there)
// and with observations on both sides of the Huber threshold (the kernel is inside the cost).
TEST(OptimizeJacobians, BatchPoseCostPassesGradientChecker) {
  for (const bool stereo : {false, true}) {
    SyntheticPoseOnlySpec spec{.numObservations = 40, .stereo = stereo, .seed = 21};
    spec.noise.pyramidLevels = 4;
    spec.noise.outlierRatio = 0.3;
    const SyntheticPoseOnly synthetic = makeSyntheticPoseOnly(spec);
    PoseBatchCost cost(synthetic.problem.camera, synthetic.problem.observations,
                       synthetic.problem.T_c_w);
    cost.setHuberDeltas(std::sqrt(kChi2Mono), std::sqrt(kChi2Stereo));
    cost.setActive(3, false);
    const double delta[6] = {0.05, -0.1, 0.08, 0.02, -0.03, 0.04};
    const double* parameters[] = {delta};
    ceres::NumericDiffOptions numericOptions;
    const std::vector<const ceres::Manifold*>* noManifolds = nullptr;
    ceres::GradientChecker checker(&cost, noManifolds, numericOptions);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, 1e-6, &results)) << results.error_log;

    // Some observations must be in the robust (Huber) region for this to test the kernel.
    double residuals[3 * 40];
    ASSERT_TRUE(cost.Evaluate(parameters, residuals, nullptr));
    int robust = 0;
    int row = 0;
    for (const PoseObservation& obs : synthetic.problem.observations) {
      const int n = obs.isStereo() ? 3 : 2;
      double s = 0.0;
      for (int k = 0; k < n; ++k) s += residuals[row + k] * residuals[row + k];
      if (s > kChi2Stereo) ++robust;
      row += n;
    }
    EXPECT_GT(robust, 5);
  }
}

TEST(OptimizeJacobians, BatchPoseCostHasHuberObjective) {
  // |r'|^2 must equal rho(|r|^2) for each observation: compare with ceres::HuberLoss.
  const SyntheticPoseOnly synthetic =
      makeSyntheticPoseOnly({.numObservations = 30, .noise = {.outlierRatio = 0.5}, .seed = 2});
  PoseBatchCost robust(synthetic.problem.camera, synthetic.problem.observations,
                       synthetic.T_c_w_true);
  PoseBatchCost plain(synthetic.problem.camera, synthetic.problem.observations,
                      synthetic.T_c_w_true);
  const double deltaHuber = std::sqrt(kChi2Mono);
  robust.setHuberDeltas(deltaHuber, deltaHuber);
  const double delta[6] = {0, 0, 0, 0, 0, 0};
  const double* parameters[] = {delta};
  double r[60], p[60];
  ASSERT_TRUE(robust.Evaluate(parameters, r, nullptr));
  ASSERT_TRUE(plain.Evaluate(parameters, p, nullptr));
  const ceres::HuberLoss huber(deltaHuber);
  for (int i = 0; i < 30; ++i) {
    const double s = p[2 * i] * p[2 * i] + p[2 * i + 1] * p[2 * i + 1];
    double rho[3];
    huber.Evaluate(s, rho);
    EXPECT_NEAR(r[2 * i] * r[2 * i] + r[2 * i + 1] * r[2 * i + 1], rho[0], 1e-9 * (1 + rho[0]));
  }
}

TEST(OptimizeJacobians, PointBehindCameraIsRejected) {
  const BundleReprojectionCost<2> cost(syntheticCamera(), {100.0, 100.0}, 1.0);
  const PoseBlock pose = toPoseBlock(SE3::Identity());
  const Eigen::Vector3d behind(0.1, 0.2, -2.0);
  const double* parameters[] = {pose.data(), behind.data()};
  double residual[2];
  EXPECT_FALSE(cost.Evaluate(parameters, residual, nullptr));
}

TEST(OptimizeJacobians, DisabledCostIsZero) {
  PoseReprojectionCost<3> cost(syntheticCamera(), {0.3, 0.1, 4.0}, {10.0, 20.0, 5.0}, 1.0);
  cost.setEnabled(false);
  const PoseBlock pose = toPoseBlock(SE3::Identity());
  const double* parameters[] = {pose.data()};
  double residual[3] = {1, 1, 1};
  double jacobian[3 * kPoseBlockSize];
  std::fill(std::begin(jacobian), std::end(jacobian), 1.0);
  double* jacobians[] = {jacobian};
  ASSERT_TRUE(cost.Evaluate(parameters, residual, jacobians));
  for (double r : residual) EXPECT_EQ(r, 0.0);
  for (double j : jacobian) EXPECT_EQ(j, 0.0);
}

TEST(OptimizeSE3Manifold, PlusMinusRoundTrip) {
  const SE3LeftManifold& manifold = *se3LeftManifold();
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    const PoseBlock x = toPoseBlock(perturbPose(SE3::Identity(), 2.0, 120.0, seed));
    const PoseBlock y = toPoseBlock(perturbPose(SE3::Identity(), 2.0, 120.0, seed + 100));
    double delta[6];
    ASSERT_TRUE(manifold.Minus(y.data(), x.data(), delta));
    PoseBlock back;
    ASSERT_TRUE(manifold.Plus(x.data(), delta, back.data()));
    EXPECT_TRUE(fromPoseBlock(back.data()).isApprox(fromPoseBlock(y.data()), 1e-12));

    const double step[6] = {0.1, -0.2, 0.3, 0.5, -1.0, 2.0};
    PoseBlock moved;
    ASSERT_TRUE(manifold.Plus(x.data(), step, moved.data()));
    double recovered[6];
    ASSERT_TRUE(manifold.Minus(moved.data(), x.data(), recovered));
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(recovered[i], step[i], 1e-12);
  }
}

TEST(OptimizeSE3Manifold, ExpLogRoundTrip) {
  for (const Eigen::Vector3d& omega :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e-12, 0, 2e-12), Eigen::Vector3d(0.3, -0.2, 0.1),
        Eigen::Vector3d(0, 3.1, 0)}) {
    EXPECT_TRUE(logSO3(expSO3(omega)).isApprox(omega, 1e-12) || omega.norm() < 1e-11)
        << omega.transpose();
    EXPECT_NEAR(expSO3(omega).norm(), 1.0, 1e-15);
  }
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(logSO3(Eigen::Quaterniond(-q.coeffs())).isApprox(Eigen::Vector3d(0, 0.4, 0)));
}

TEST(OptimizeSE3Manifold, PoseBlockRoundTrip) {
  const SE3 T = perturbPose(SE3::Identity(), 3.0, 170.0, 7);
  EXPECT_TRUE(fromPoseBlock(toPoseBlock(T).data()).isApprox(T, 1e-14));
}

}  // namespace
}  // namespace lumaslam::optimize
