#include "lumaslam/optimize/pose_only.h"

#include <algorithm>
#include <array>
#include <memory>
#include <utility>
#include <vector>

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

// After a round: every observation classified by chi-square at T_c_w, enable(i, inlier) takes
// the inliers into the next round and leaves the outliers out. Returns the number of inliers.
template <typename Enable>
int classifyObservations(const PoseOnlyProblem& problem, const PoseOnlyOptions& options,
                         const SE3& T_c_w, std::vector<bool>& isOutlier, Enable enable) {
  int numInliers = 0;
  for (std::size_t i = 0; i < problem.observations.size(); ++i) {
    const PoseObservation& obs = problem.observations[i];
    const double threshold =
        obs.isStereo() ? options.thresholds.chi2Stereo : options.thresholds.chi2Mono;
    const bool outlier = !(observationChi2(problem.camera, T_c_w, obs) <= threshold);
    isOutlier[i] = outlier;
    enable(i, !outlier);
    if (!outlier) ++numInliers;
  }
  return numInliers;
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
    numInliers =
        classifyObservations(problem, options, T_c_w, result.isOutlier,
                             [&](std::size_t i, bool inlier) { active[i] = inlier ? 1 : 0; });
    if (numInliers < options.minInliers) break;
  }
  result.numInliers = numInliers;
  result.success = numInliers >= options.minInliers;
  if (result.success) result.T_c_w = T_c_w;
  return result;
}

ceres::Problem::Options nonOwningProblemOptions() {
  ceres::Problem::Options problemOptions;
  problemOptions.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problemOptions.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return problemOptions;
}

ceres::Solver::Options solverOptionsOf(const PoseOnlyOptions& options) {
  ceres::Solver::Options solverOptions;
  solverOptions.linear_solver_type =
      options.solver == DenseSolver::kQR ? ceres::DENSE_QR : ceres::DENSE_NORMAL_CHOLESKY;
  solverOptions.max_num_iterations = options.iterationsPerRound;
  solverOptions.num_threads = 1;
  solverOptions.logging_type = ceres::SILENT;
  solverOptions.minimizer_progress_to_stdout = false;
  return solverOptions;
}

// The Ceres problem of the pose. Batched: a 6-vector update of a reference pose
// (pose_batch_cost.h). Per observation: the SE3 block with its manifold (se3_parameter.h).
class CeresPoseProblem {
 public:
  CeresPoseProblem(const PoseOnlyProblem& problem, const PoseOnlyOptions& options)
      : pose_(toPoseBlock(problem.T_c_w)),
        losses_(options.thresholds),
        ceresProblem_(nonOwningProblemOptions()) {
    if (options.batchResiduals) {
      batchCost_ = new PoseBatchCost(problem.camera, problem.observations, problem.T_c_w);
      batchCost_->setHuberDeltas(options.thresholds.huberDeltaMono(),
                                 options.thresholds.huberDeltaStereo());
      ceresProblem_.AddResidualBlock(batchCost_, nullptr, delta_.data());
    } else {
      addObservationResiduals(problem);
    }
  }

  void setEnabled(int i, bool enabled) {
    if (batchCost_) batchCost_->setActive(i, enabled);
    if (!monoCosts_.empty() && monoCosts_[i]) monoCosts_[i]->setEnabled(enabled);
    if (!stereoCosts_.empty() && stereoCosts_[i]) stereoCosts_[i]->setEnabled(enabled);
  }
  SE3 currentPose() const {
    return batchCost_ ? batchCost_->poseAt(delta_.data()) : fromPoseBlock(pose_.data());
  }
  void dropKernels() {
    losses_.dropKernels();
    if (batchCost_) batchCost_->setHuberDeltas(0.0, 0.0);
  }
  // One round's solve; returns its iterations.
  int solve(const ceres::Solver::Options& solverOptions) {
    ceres::Solver::Summary summary;
    ceres::Solve(solverOptions, &ceresProblem_, &summary);
    // summary.iterations includes the initial evaluation (iteration 0).
    return std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  }
  // The pose the round reached; the batched update restarts from it.
  SE3 recentre() {
    const SE3 T_c_w = currentPose();
    if (batchCost_) {
      batchCost_->setReference(T_c_w);
      delta_.fill(0.0);
    }
    return T_c_w;
  }

 private:
  void addObservationResiduals(const PoseOnlyProblem& problem) {
    const auto& observations = problem.observations;
    ceresProblem_.AddParameterBlock(pose_.data(), kPoseBlockSize, se3LeftManifold());
    monoCosts_.assign(observations.size(), nullptr);
    stereoCosts_.assign(observations.size(), nullptr);
    for (int i = 0; i < static_cast<int>(observations.size()); ++i) {
      const PoseObservation& obs = observations[i];
      if (obs.isStereo()) {
        stereoCosts_[i] = new PoseReprojectionCost<3>(
            problem.camera, obs.X_w, {obs.uv.x(), obs.uv.y(), obs.uRight}, obs.invSigma2);
        ceresProblem_.AddResidualBlock(stereoCosts_[i], &losses_.stereo, pose_.data());
      } else {
        monoCosts_[i] = new PoseReprojectionCost<2>(problem.camera, obs.X_w, obs.uv, obs.invSigma2);
        ceresProblem_.AddResidualBlock(monoCosts_[i], &losses_.mono, pose_.data());
      }
    }
  }

  std::array<double, PoseBatchCost::kParameters> delta_{};
  PoseBlock pose_;
  SharedLosses losses_;
  ceres::Problem ceresProblem_;
  // Non-owning: the problem owns the costs; we only toggle observations between rounds.
  PoseBatchCost* batchCost_ = nullptr;
  std::vector<PoseReprojectionCost<2>*> monoCosts_;
  std::vector<PoseReprojectionCost<3>*> stereoCosts_;
};

// The rounds of optimizePose with ceres::Solve for each round's solve.
PoseOnlyResult optimizePoseCeres(const PoseOnlyProblem& problem, const PoseOnlyOptions& options,
                                 PoseOnlyResult result) {
  const auto& observations = problem.observations;
  const int numObservations = static_cast<int>(observations.size());
  CeresPoseProblem pose(problem, options);
  const ceres::Solver::Options solverOptions = solverOptionsOf(options);
  int numInliers = 0;
  for (int round = 0; round < options.rounds; ++round) {
    // A point that is behind the current pose cannot be evaluated: exclude it up front.
    const SE3 T_before = pose.currentPose();
    for (int i = 0; i < numObservations; ++i) {
      if (!result.isOutlier[i] && !((T_before * observations[i].X_w).z() > kMinProjectionDepth)) {
        result.isOutlier[i] = true;
        pose.setEnabled(i, false);
      }
    }
    if (round == options.rounds - 1) pose.dropKernels();
    result.iterations += pose.solve(solverOptions);
    const SE3 T_c_w = pose.recentre();
    numInliers = classifyObservations(
        problem, options, T_c_w, result.isOutlier,
        [&](std::size_t i, bool inlier) { pose.setEnabled(static_cast<int>(i), inlier); });
    if (numInliers < options.minInliers) break;
  }
  result.numInliers = numInliers;
  result.success = numInliers >= options.minInliers;
  if (result.success) result.T_c_w = pose.currentPose();
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
  return optimizePoseCeres(problem, options, std::move(result));
}

}  // namespace lumaslam::optimize
