// Local bundle adjustment on a synthetic scene with known ground truth: 10 keyframes along a
// path (the first two fixed at the truth, which fixes the gauge and, for mono, the scale),
// 500 points, 1 px noise, 5% wrong matches, perturbed poses (5 cm, 1 deg) and points (10 cm).
#include <algorithm>
#include <atomic>
#include <cmath>

#include <ceres/autodiff_cost_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/optimize/abort_callback.h"
#include "lumaslam/optimize/local_ba.h"
#include "lumaslam/optimize/reprojection_error.h"
#include "lumaslam/optimize/synthetic_problems.h"

namespace lumaslam::optimize {
namespace {

// Per-coordinate RMSE [px] of the reprojection errors of true inliers (~1 px for 1 px noise),
// leaving out those in `skip` (e.g. the observations the BA flagged).
double inlierRmse(const SyntheticBundle& scene, const std::vector<SE3>& T_c_w,
                  const std::vector<Eigen::Vector3d>& X_w, const std::vector<bool>& skip) {
  const LocalBAProblem& problem = scene.problem;
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < problem.observations.size(); ++i) {
    if (scene.isInjectedOutlier[i] || skip[i]) continue;
    const BAObservation& obs = problem.observations[i];
    const int k = static_cast<int>(obs.keyFrameId - problem.keyFrames.front().id);
    const int j = static_cast<int>(obs.pointId - problem.points.front().id);
    const Eigen::Vector3d P_c = T_c_w[k] * X_w[j];
    if (obs.isStereo()) {
      Measurement<3> e = Measurement<3>::Zero();
      EXPECT_TRUE(
          reprojectionError<3>(problem.camera, P_c, {obs.uv.x(), obs.uv.y(), obs.uRight}, e));
      sum += e.squaredNorm();
      count += 3;
    } else {
      Measurement<2> e = Measurement<2>::Zero();
      EXPECT_TRUE(reprojectionError<2>(problem.camera, P_c, obs.uv, e));
      sum += e.squaredNorm();
      count += 2;
    }
  }
  return std::sqrt(sum / count);
}

double meanPoseError(const std::vector<SE3>& T_c_w, const std::vector<SE3>& truth) {
  double sum = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k)
    sum += (T_c_w[k].inverse().translation() - truth[k].inverse().translation()).norm();
  return sum / truth.size();
}

// Median, because a point whose few observations are mostly wrong matches legitimately runs
// away (the mapper culls it).
double medianPointError(const std::vector<Eigen::Vector3d>& X_w,
                        const std::vector<Eigen::Vector3d>& truth) {
  std::vector<double> errors;
  for (std::size_t j = 0; j < truth.size(); ++j) errors.push_back((X_w[j] - truth[j]).norm());
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return errors[errors.size() / 2];
}

std::vector<SE3> posesOf(const LocalBAProblem& problem) {
  std::vector<SE3> poses;
  for (const BAKeyFrame& kf : problem.keyFrames) poses.push_back(kf.T_c_w);
  return poses;
}

std::vector<Eigen::Vector3d> pointsOf(const LocalBAProblem& problem) {
  std::vector<Eigen::Vector3d> points;
  for (const BAPoint& p : problem.points) points.push_back(p.X_w);
  return points;
}

void expectConverges(bool stereo, std::uint32_t seed) {
  const SyntheticBundle scene = makeSyntheticBundle({.stereo = stereo, .seed = seed});
  ASSERT_GT(scene.problem.observations.size(), 2000u);
  const std::vector<bool> none(scene.problem.observations.size(), false);
  const double rmseBefore =
      inlierRmse(scene, posesOf(scene.problem), pointsOf(scene.problem), none);
  const double poseErrorBefore = meanPoseError(posesOf(scene.problem), scene.T_c_w_true);
  const double pointErrorBefore = medianPointError(pointsOf(scene.problem), scene.X_w_true);

  const LocalBAResult result = optimizeLocalBundle(scene.problem, {.maxIterations = 20});
  ASSERT_EQ(result.T_c_w.size(), scene.problem.keyFrames.size());
  ASSERT_EQ(result.X_w.size(), scene.problem.points.size());
  EXPECT_FALSE(result.aborted);
  EXPECT_LT(result.finalCost, result.initialCost);

  // Over the true inliers the BA kept (>= 90% of them, checked below).
  const double rmseAfter = inlierRmse(scene, result.T_c_w, result.X_w, result.isOutlier);
  const double poseErrorAfter = meanPoseError(result.T_c_w, scene.T_c_w_true);
  const double pointErrorAfter = medianPointError(result.X_w, scene.X_w_true);
  SCOPED_TRACE(::testing::Message()
               << (stereo ? "stereo" : "mono") << " seed " << seed << ": rmse " << rmseBefore
               << " -> " << rmseAfter << ", pose error " << poseErrorBefore << " -> "
               << poseErrorAfter << ", point error " << pointErrorBefore << " -> "
               << pointErrorAfter);
  EXPECT_GT(rmseBefore, 5.0);
  EXPECT_LT(rmseAfter, 1.15);  // the noise is 1 px per coordinate
  EXPECT_GT(rmseAfter, 0.75);  // and not far below it
  EXPECT_LT(poseErrorAfter, 0.2 * poseErrorBefore);
  EXPECT_LT(poseErrorAfter, 0.01);
  EXPECT_LT(pointErrorAfter, 0.5 * pointErrorBefore);
  for (std::size_t k = 0; k < scene.problem.keyFrames.size(); ++k) {
    if (scene.problem.keyFrames[k].fixed) {
      EXPECT_TRUE(result.T_c_w[k].isApprox(scene.problem.keyFrames[k].T_c_w, 1e-12));
    }
  }

  int outliers = 0, caught = 0, inliers = 0, kept = 0;
  for (std::size_t i = 0; i < scene.isInjectedOutlier.size(); ++i) {
    if (scene.isInjectedOutlier[i]) {
      ++outliers;
      caught += result.isOutlier[i];
    } else {
      ++inliers;
      kept += !result.isOutlier[i];
    }
  }
  EXPECT_GE(double(caught) / outliers, 0.95);
  EXPECT_GE(double(kept) / inliers, 0.9);
  EXPECT_EQ(result.numOutliers, caught + (inliers - kept));
}

TEST(OptimizeLocalBA, MonoConvergesToNoiseLevel) {
  for (std::uint32_t seed = 1; seed <= 2; ++seed) expectConverges(false, seed);
}

TEST(OptimizeLocalBA, StereoConvergesToNoiseLevel) {
  for (std::uint32_t seed = 1; seed <= 2; ++seed) expectConverges(true, seed);
}

TEST(OptimizeLocalBA, SchurSolversAgree) {
  const SyntheticBundle scene = makeSyntheticBundle({.numPoints = 200, .seed = 5});
  const LocalBAResult sparse =
      optimizeLocalBundle(scene.problem, {.maxIterations = 30, .solver = SchurSolver::kSparse});
  for (const SchurSolver solver : {SchurSolver::kIterative, SchurSolver::kDense}) {
    const LocalBAResult other =
        optimizeLocalBundle(scene.problem, {.maxIterations = 30, .solver = solver});
    EXPECT_NEAR(other.finalCost, sparse.finalCost, 1e-3 * sparse.finalCost);
    EXPECT_LT(meanPoseError(other.T_c_w, sparse.T_c_w), 1e-4);
  }
}

TEST(OptimizeLocalBA, PresetAbortFlagReturnsInputUnchanged) {
  const SyntheticBundle scene = makeSyntheticBundle({.numPoints = 100});
  const std::atomic<bool> abort{true};
  const LocalBAResult result = optimizeLocalBundle(scene.problem, {.abort = &abort});
  EXPECT_TRUE(result.aborted);
  EXPECT_EQ(result.iterations, 0);
  for (std::size_t k = 0; k < result.T_c_w.size(); ++k)
    EXPECT_TRUE(result.T_c_w[k].isApprox(scene.problem.keyFrames[k].T_c_w));
  for (std::size_t j = 0; j < result.X_w.size(); ++j)
    EXPECT_EQ(result.X_w[j], scene.problem.points[j].X_w);
}

// The flag raised mid-solve (here by the cost function itself, deterministically, on its 10th
// evaluation) stops Ceres after the current iteration, as the mapper's abort does. Unaborted, this
// solve takes 36 iterations (67 evaluations).
struct RaisesFlagAfter {
  std::atomic<bool>* flag;
  int* evaluations;
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    if (++*evaluations >= 10) flag->store(true);
    residual[0] = T(10.0) - x[0];
    residual[1] = x[0] * x[0] - T(3.0);  // slow to converge from far away
    return true;
  }
};

TEST(OptimizeLocalBA, AbortFlagRaisedDuringSolveStopsIt) {
  std::atomic<bool> abort{false};
  int evaluations = 0;
  double x = 1e6;
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RaisesFlagAfter, 2, 1>(
                               new RaisesFlagAfter{&abort, &evaluations}),
                           nullptr, &x);
  AbortCallback callback(&abort);
  ceres::Solver::Options options;
  options.max_num_iterations = 1000;
  options.function_tolerance = options.gradient_tolerance = options.parameter_tolerance = 0.0;
  options.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  EXPECT_TRUE(callback.aborted());
  EXPECT_EQ(summary.termination_type, ceres::USER_SUCCESS);
  EXPECT_LT(summary.iterations.size(), 15u);
  EXPECT_GE(evaluations, 10);
}

TEST(OptimizeLocalBA, IterationBudgetIsRespected) {
  const SyntheticBundle scene = makeSyntheticBundle({.numPoints = 200, .seed = 3});
  const LocalBAResult result =
      optimizeLocalBundle(scene.problem, {.maxIterations = 2, .refinementIterations = 0});
  EXPECT_LE(result.iterations, 2);
  EXPECT_GE(result.iterations, 1);
  EXPECT_LT(result.finalCost, result.initialCost);
}

TEST(OptimizeLocalBA, RejectsInconsistentInput) {
  const SyntheticBundle scene = makeSyntheticBundle({.numPoints = 50});
  LocalBAProblem unknownKeyFrame = scene.problem;
  unknownKeyFrame.observations[4].keyFrameId = 999999;
  const std::string message = test::errorOf([&] { optimizeLocalBundle(unknownKeyFrame); });
  EXPECT_NE(message.find("unknown keyframe id 999999"), std::string::npos) << message;
  LocalBAProblem duplicatePoint = scene.problem;
  duplicatePoint.points[1].id = duplicatePoint.points[0].id;
  EXPECT_THROW(optimizeLocalBundle(duplicatePoint), Error);
  LocalBAProblem unknownPoint = scene.problem;
  unknownPoint.observations[0].pointId = 42;
  EXPECT_THROW(optimizeLocalBundle(unknownPoint), Error);
  LocalBAProblem stereoWithoutBaseline = scene.problem;
  stereoWithoutBaseline.camera.bf = 0.0;
  stereoWithoutBaseline.observations[0].uRight = 10.0;
  EXPECT_THROW(optimizeLocalBundle(stereoWithoutBaseline), Error);
}

TEST(OptimizeLocalBA, EmptyProblemIsANoOp) {
  const LocalBAProblem problem{.camera = syntheticCamera()};
  const LocalBAResult result = optimizeLocalBundle(problem);
  EXPECT_TRUE(result.T_c_w.empty());
  EXPECT_TRUE(result.isOutlier.empty());
  EXPECT_EQ(result.iterations, 0);
}

}  // namespace
}  // namespace lumaslam::optimize
