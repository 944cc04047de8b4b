#include "lumaslam/optimize/pose_only.h"

#include <algorithm>
#include <array>
#include <memory>

#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "lumaslam/core/error.h"
#include "lumaslam/optimize/pose_batch_cost.h"
#include "lumaslam/optimize/pose_levenberg_marquardt.h"
#include "lumaslam/optimize/reprojection_cost.h"
#include "lumaslam/optimize/se3_parameter.h"

namespace lumaslam::optimize {

namespace {

// Huber kernels shared by all residuals of one kind, so the last round can drop them at once.
struct SharedLosses {
  explicit SharedLosses(const RobustThresholds& thresholds)
      : mono(new ceres::HuberLoss(thresholds.huberDeltaMono()), ceres::TAKE_OWNERSHIP),
        stereo(new ceres::HuberLoss(thresholds.huberDeltaStereo()), ceres::TAKE_OWNERSHIP) {}
  void dropKernels() {
    mono.Reset(nullptr, ceres::TAKE_OWNERSHIP);
    stereo.Reset(nullptr, ceres::TAKE_OWNERSHIP);
  }
  ceres::LossFunctionWrapper mono;
  ceres::LossFunctionWrapper stereo;
};

double observationChi2(const CameraIntrinsics& camera, const SE3& T_c_w,
                       const PoseObservation& obs) {
  const Eigen::Vector3d P_c = T_c_w * obs.X_w;
  if (obs.isStereo())
    return reprojectionChi2<3>(camera, P_c, {obs.uv.x(), obs.uv.y(), obs.uRight}, obs.invSigma2);
  return reprojectionChi2<2>(camera, P_c, obs.uv, obs.invSigma2);
}

void validate(const PoseOnlyProblem& problem, const PoseOnlyOptions& options) {
  const CameraIntrinsics& c = problem.camera;
  if (!(c.fx > 0.0) || !(c.fy > 0.0))
    fail("pose-only optimisation: camera fx={} fy={} must be positive", c.fx, c.fy);
  if (options.rounds < 1 || options.iterationsPerRound < 1)
    fail("pose-only optimisation: rounds={} and iterationsPerRound={} must be >= 1", options.rounds,
         options.iterationsPerRound);
  for (std::size_t i = 0; i < problem.observations.size(); ++i) {
    const PoseObservation& obs = problem.observations[i];
    if (!(obs.invSigma2 > 0.0) || !obs.X_w.allFinite() || !obs.uv.allFinite())
      fail("pose-only optimisation: observation {} is invalid (invSigma2={}, non-finite values?)",
           i, obs.invSigma2);
    if (obs.isStereo() && !(c.bf > 0.0))
      fail("pose-only optimisation: observation {} is stereo but camera bf={} is not positive", i,
           c.bf);
  }
}

// The rounds of optimizePose with minimizePoseLevenbergMarquardt for each round's solve.
PoseOnlyResult optimizePoseLevenbergMarquardt(const PoseOnlyProblem& problem,
                                              const PoseOnlyOptions& options,
                                              PoseOnlyResult result) {
  const auto& observations = problem.observations;
  const std::size_t count = observations.size();
  std::vector<char> active(count, 1);
  SE3 T_c_w = problem.T_c_w;
  int numInliers = 0;
  for (int round = 0; round < options.rounds; ++round) {
    for (std::size_t i = 0; i < count; ++i) {
      if (active[i] && !((T_c_w * observations[i].X_w).z() > kMinProjectionDepth)) {
        result.isOutlier[i] = true;
        active[i] = 0;
      }
    }
    const bool robust = round < options.rounds - 1;
    const PoseRoundResult solved = minimizePoseLevenbergMarquardt(
        problem.camera, observations, active, T_c_w,
        robust ? options.thresholds.huberDeltaMono() : 0.0,
        robust ? options.thresholds.huberDeltaStereo() : 0.0, options.iterationsPerRound);
    T_c_w = solved.T_c_w;
    result.iterations += solved.iterations;
    numInliers = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const PoseObservation& obs = observations[i];
      const double threshold =
          obs.isStereo() ? options.thresholds.chi2Stereo : options.thresholds.chi2Mono;
      const bool outlier = !(observationChi2(problem.camera, T_c_w, obs) <= threshold);
      result.isOutlier[i] = outlier;
      active[i] = outlier ? 0 : 1;
      if (!outlier) ++numInliers;
    }
    if (numInliers < options.minInliers) break;
  }
  result.numInliers = numInliers;
  result.success = numInliers >= options.minInliers;
  if (result.success) result.T_c_w = T_c_w;
  return result;
}

}  // namespace

PoseOnlyResult optimizePose(const PoseOnlyProblem& problem, const PoseOnlyOptions& options) {
  validate(problem, options);
  const auto& observations = problem.observations;
  const int numObservations = static_cast<int>(observations.size());
  PoseOnlyResult result;
  result.T_c_w = problem.T_c_w;
  result.isOutlier.assign(observations.size(), false);
  if (numObservations < 3) {
    result.isOutlier.assign(observations.size(), true);
    return result;
  }
  if (options.backend == PoseBackend::kLevenbergMarquardt)
    return optimizePoseLevenbergMarquardt(problem, options, std::move(result));

  // Batched: a 6-vector update of a reference pose (pose_batch_cost.h). Per observation: the
  // SE3 block with its manifold (se3_parameter.h).
  std::array<double, PoseBatchCost::kParameters> delta{};
  PoseBlock pose = toPoseBlock(problem.T_c_w);
  SharedLosses losses(options.thresholds);
  ceres::Problem::Options problemOptions;
  problemOptions.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problemOptions.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem ceresProblem(problemOptions);

  // Non-owning: the problem owns the costs; we only toggle observations between rounds.
  PoseBatchCost* batchCost = nullptr;
  std::vector<PoseReprojectionCost<2>*> monoCosts;
  std::vector<PoseReprojectionCost<3>*> stereoCosts;
  if (options.batchResiduals) {
    batchCost = new PoseBatchCost(problem.camera, observations, problem.T_c_w);
    batchCost->setHuberDeltas(options.thresholds.huberDeltaMono(),
                              options.thresholds.huberDeltaStereo());
    ceresProblem.AddResidualBlock(batchCost, nullptr, delta.data());
  } else {
    ceresProblem.AddParameterBlock(pose.data(), kPoseBlockSize, se3LeftManifold());
    monoCosts.assign(observations.size(), nullptr);
    stereoCosts.assign(observations.size(), nullptr);
    for (int i = 0; i < numObservations; ++i) {
      const PoseObservation& obs = observations[i];
      if (obs.isStereo()) {
        stereoCosts[i] = new PoseReprojectionCost<3>(
            problem.camera, obs.X_w, {obs.uv.x(), obs.uv.y(), obs.uRight}, obs.invSigma2);
        ceresProblem.AddResidualBlock(stereoCosts[i], &losses.stereo, pose.data());
      } else {
        monoCosts[i] = new PoseReprojectionCost<2>(problem.camera, obs.X_w, obs.uv, obs.invSigma2);
        ceresProblem.AddResidualBlock(monoCosts[i], &losses.mono, pose.data());
      }
    }
  }
  const auto setEnabled = [&](int i, bool enabled) {
    if (batchCost) batchCost->setActive(i, enabled);
    if (!monoCosts.empty() && monoCosts[i]) monoCosts[i]->setEnabled(enabled);
    if (!stereoCosts.empty() && stereoCosts[i]) stereoCosts[i]->setEnabled(enabled);
  };
  const auto currentPose = [&] {
    return batchCost ? batchCost->poseAt(delta.data()) : fromPoseBlock(pose.data());
  };
  const auto dropKernels = [&] {
    losses.dropKernels();
    if (batchCost) batchCost->setHuberDeltas(0.0, 0.0);
  };

  ceres::Solver::Options solverOptions;
  solverOptions.linear_solver_type =
      options.solver == DenseSolver::kQR ? ceres::DENSE_QR : ceres::DENSE_NORMAL_CHOLESKY;
  solverOptions.max_num_iterations = options.iterationsPerRound;
  solverOptions.num_threads = 1;
  solverOptions.logging_type = ceres::SILENT;
  solverOptions.minimizer_progress_to_stdout = false;

  int numInliers = 0;
  for (int round = 0; round < options.rounds; ++round) {
    // A point that is behind the current pose cannot be evaluated: exclude it up front.
    const SE3 T_before = currentPose();
    for (int i = 0; i < numObservations; ++i) {
      if (!result.isOutlier[i] && !((T_before * observations[i].X_w).z() > kMinProjectionDepth)) {
        result.isOutlier[i] = true;
        setEnabled(i, false);
      }
    }
    if (round == options.rounds - 1) dropKernels();
    ceres::Solver::Summary summary;
    ceres::Solve(solverOptions, &ceresProblem, &summary);
    // summary.iterations includes the initial evaluation (iteration 0).
    result.iterations += std::max(0, static_cast<int>(summary.iterations.size()) - 1);

    const SE3 T_c_w = currentPose();
    if (batchCost) {
      batchCost->setReference(T_c_w);
      delta.fill(0.0);
    }
    numInliers = 0;
    for (int i = 0; i < numObservations; ++i) {
      const PoseObservation& obs = observations[i];
      const double threshold =
          obs.isStereo() ? options.thresholds.chi2Stereo : options.thresholds.chi2Mono;
      const bool outlier = !(observationChi2(problem.camera, T_c_w, obs) <= threshold);
      result.isOutlier[i] = outlier;
      setEnabled(i, !outlier);
      if (!outlier) ++numInliers;
    }
    if (numInliers < options.minInliers) break;
  }

  result.numInliers = numInliers;
  result.success = numInliers >= options.minInliers;
  if (result.success) result.T_c_w = currentPose();
  return result;
}

}  // namespace lumaslam::optimize
