// Pose-only optimisation on synthetic 2D-3D matches with known ground truth: pixel noise
// (1 px at level 0), 20% gross outliers, initial pose off by 5 cm / 3 deg.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/optimize/pose_only.h"
#include "lumaslam/optimize/synthetic_problems.h"

namespace lumaslam::optimize {
namespace {

double translationError(const SE3& a, const SE3& b) {
  return (a.inverse().translation() - b.inverse().translation()).norm();
}

double rotationErrorDeg(const SE3& a, const SE3& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / std::numbers::pi;
}

struct Classification {
  double outlierRecall;  // injected outliers flagged
  double inlierKept;     // true inliers not flagged
};

Classification classify(const std::vector<bool>& injected, const std::vector<bool>& flagged) {
  int outliers = 0, caught = 0, inliers = 0, kept = 0;
  for (std::size_t i = 0; i < injected.size(); ++i) {
    if (injected[i]) {
      ++outliers;
      if (flagged[i]) ++caught;
    } else {
      ++inliers;
      if (!flagged[i]) ++kept;
    }
  }
  return {outliers ? double(caught) / outliers : 1.0, inliers ? double(kept) / inliers : 1.0};
}

void expectRecovers(const SyntheticPoseOnlySpec& spec, const PoseOnlyOptions& options = {}) {
  const SyntheticPoseOnly synthetic = makeSyntheticPoseOnly(spec);
  ASSERT_GT(translationError(synthetic.problem.T_c_w, synthetic.T_c_w_true), 0.04);
  const PoseOnlyResult result = optimizePose(synthetic.problem, options);
  ASSERT_TRUE(result.success);
  EXPECT_LT(translationError(result.T_c_w, synthetic.T_c_w_true), 0.01) << "seed " << spec.seed;
  EXPECT_LT(rotationErrorDeg(result.T_c_w, synthetic.T_c_w_true), 0.2) << "seed " << spec.seed;
  ASSERT_EQ(result.isOutlier.size(), synthetic.isInjectedOutlier.size());
  const Classification c = classify(synthetic.isInjectedOutlier, result.isOutlier);
  EXPECT_GE(c.outlierRecall, 0.95) << "seed " << spec.seed;
  // chi2 at 95% rejects ~5% of true inliers by design.
  EXPECT_GE(c.inlierKept, 0.88) << "seed " << spec.seed;
  int flaggedInliers = 0;
  for (bool outlier : result.isOutlier) flaggedInliers += outlier ? 0 : 1;
  EXPECT_EQ(result.numInliers, flaggedInliers);
}

TEST(OptimizePoseOnly, MonoRecoversPoseAndOutliers) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed)
    expectRecovers({.numObservations = 300, .stereo = false, .seed = seed});
}

TEST(OptimizePoseOnly, StereoRecoversPoseAndOutliers) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed)
    expectRecovers({.numObservations = 300, .stereo = true, .seed = seed});
}

TEST(OptimizePoseOnly, PyramidLevelsWeightTheResiduals) {
  // Noise grows with the level (sigma 1.2^l); invSigma2 compensates so chi2 stays calibrated.
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    SyntheticPoseOnlySpec spec{.numObservations = 500, .stereo = seed % 2 == 0, .seed = seed};
    spec.noise.pyramidLevels = 8;
    expectRecovers(spec);
  }
}

TEST(OptimizePoseOnly, ResidualLayoutsAndSolversAgree) {
  // Batched (Huber inside one block) and per-observation (ceres::HuberLoss) minimise the same
  // objective; QR and normal equations solve the same linear systems.
  for (const bool stereo : {false, true}) {
    const SyntheticPoseOnly synthetic =
        makeSyntheticPoseOnly({.numObservations = 300, .stereo = stereo, .seed = 17});
    const PoseOnlyResult batched = optimizePose(synthetic.problem);
    for (const PoseOnlyOptions& options :
         {PoseOnlyOptions{.batchResiduals = false}, PoseOnlyOptions{.solver = DenseSolver::kQR}}) {
      const PoseOnlyResult other = optimizePose(synthetic.problem, options);
      EXPECT_LT(translationError(other.T_c_w, batched.T_c_w), 1e-4);
      EXPECT_LT(rotationErrorDeg(other.T_c_w, batched.T_c_w), 1e-3);
      EXPECT_EQ(other.isOutlier, batched.isOutlier);
    }
  }
}

TEST(OptimizePoseOnly, LevenbergMarquardtBackendRecoversPoseAndOutliers) {
  const PoseOnlyOptions options{.backend = PoseBackend::kLevenbergMarquardt};
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    expectRecovers({.numObservations = 300, .stereo = seed % 2 == 0, .seed = seed}, options);
    SyntheticPoseOnlySpec levels{.numObservations = 500, .stereo = seed % 2 == 1, .seed = seed};
    levels.noise.pyramidLevels = 8;
    expectRecovers(levels, options);
  }
}

TEST(OptimizePoseOnly, LevenbergMarquardtBackendAgreesWithCeresHuberLoss) {
  // Same model as one ceres::HuberLoss block per observation, so the same minimum and the same
  // outlier flags, also from a far initial guess (20 cm, 8 degrees) with 30% outliers.
  for (const bool stereo : {false, true}) {
    for (std::uint32_t seed = 21; seed <= 23; ++seed) {
      SyntheticPoseOnlySpec spec{.numObservations = 600,
                                 .stereo = stereo,
                                 .initialTranslationError = 0.2,
                                 .initialRotationErrorDeg = 8.0,
                                 .seed = seed};
      spec.noise.outlierRatio = 0.3;
      spec.noise.pyramidLevels = 8;
      const SyntheticPoseOnly synthetic = makeSyntheticPoseOnly(spec);
      const PoseOnlyResult ceres =
          optimizePose(synthetic.problem, PoseOnlyOptions{.batchResiduals = false});
      const PoseOnlyResult ours = optimizePose(
          synthetic.problem, PoseOnlyOptions{.backend = PoseBackend::kLevenbergMarquardt});
      ASSERT_TRUE(ceres.success);
      ASSERT_TRUE(ours.success);
      EXPECT_LT(translationError(ours.T_c_w, ceres.T_c_w), 1e-4) << "seed " << seed;
      EXPECT_LT(rotationErrorDeg(ours.T_c_w, ceres.T_c_w), 1e-3) << "seed " << seed;
      EXPECT_EQ(ours.isOutlier, ceres.isOutlier) << "seed " << seed;
      EXPECT_LT(translationError(ours.T_c_w, synthetic.T_c_w_true), 0.01) << "seed " << seed;
    }
  }
}

TEST(OptimizePoseOnly, NoObservationsLeavesPoseAndFails) {
  PoseOnlyProblem problem{.camera = syntheticCamera(),
                          .T_c_w = perturbPose(SE3::Identity(), 1.0, 10.0, 3u)};
  const PoseOnlyResult result = optimizePose(problem);
  EXPECT_FALSE(result.success);
  EXPECT_EQ(result.numInliers, 0);
  EXPECT_TRUE(result.isOutlier.empty());
  EXPECT_TRUE(result.T_c_w.isApprox(problem.T_c_w));
}

TEST(OptimizePoseOnly, AllOutliersLeavesPoseAndFails) {
  for (const bool stereo : {false, true}) {
    SyntheticPoseOnlySpec spec{.numObservations = 200, .stereo = stereo, .seed = 11};
    spec.noise.outlierRatio = 1.0;
    const SyntheticPoseOnly synthetic = makeSyntheticPoseOnly(spec);
    const PoseOnlyResult result = optimizePose(synthetic.problem);
    EXPECT_FALSE(result.success);
    EXPECT_LT(result.numInliers, PoseOnlyOptions{}.minInliers);
    EXPECT_TRUE(result.T_c_w.isApprox(synthetic.problem.T_c_w));
    EXPECT_EQ(result.isOutlier.size(), synthetic.problem.observations.size());
  }
}

TEST(OptimizePoseOnly, PointsBehindTheCameraAreOutliers) {
  SyntheticPoseOnly synthetic = makeSyntheticPoseOnly({.numObservations = 100, .seed = 4});
  // Mirror one point through the camera centre: it is now behind the camera.
  const SE3& T = synthetic.T_c_w_true;
  auto& obs = synthetic.problem.observations[0];
  obs.X_w = T.inverse() * (-(T * obs.X_w));
  const PoseOnlyResult result = optimizePose(synthetic.problem);
  ASSERT_TRUE(result.success);
  EXPECT_TRUE(result.isOutlier[0]);
  EXPECT_LT(translationError(result.T_c_w, synthetic.T_c_w_true), 0.02);
}

TEST(OptimizePoseOnly, RejectsInvalidInput) {
  SyntheticPoseOnly synthetic = makeSyntheticPoseOnly({.numObservations = 20, .stereo = true});
  PoseOnlyProblem noBaseline = synthetic.problem;
  noBaseline.camera.bf = 0.0;
  EXPECT_THROW(optimizePose(noBaseline), Error);
  PoseOnlyProblem badFocal = synthetic.problem;
  badFocal.camera.fx = 0.0;
  EXPECT_THROW(optimizePose(badFocal), Error);
  PoseOnlyProblem badSigma = synthetic.problem;
  badSigma.observations[3].invSigma2 = 0.0;
  const std::string message = test::errorOf([&] { optimizePose(badSigma); });
  EXPECT_NE(message.find("observation 3"), std::string::npos) << message;
}

}  // namespace
}  // namespace lumaslam::optimize
