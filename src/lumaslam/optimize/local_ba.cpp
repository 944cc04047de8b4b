#include "lumaslam/optimize/local_ba.h"

#include <algorithm>
#include <memory>
#include <unordered_map>
#include <utility>

#include <ceres/loss_function.h>
#include <ceres/ordered_groups.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "lumaslam/core/error.h"
#include "lumaslam/optimize/abort_callback.h"
#include "lumaslam/optimize/reprojection_cost.h"
#include "lumaslam/optimize/se3_parameter.h"

namespace lumaslam::optimize {

namespace {

std::unordered_map<std::uint64_t, int> indexById(const auto& items, const char* what) {
  std::unordered_map<std::uint64_t, int> index;
  index.reserve(items.size());
  for (int i = 0; i < static_cast<int>(items.size()); ++i) {
    if (!index.emplace(items[i].id, i).second)
      fail("local BA: duplicate {} id {}", what, items[i].id);
  }
  return index;
}

struct ObservationIndex {
  int keyFrame;
  int point;
};

std::vector<ObservationIndex> resolveObservations(const LocalBAProblem& problem) {
  const CameraIntrinsics& c = problem.camera;
  if (!(c.fx > 0.0) || !(c.fy > 0.0))
    fail("local BA: camera fx={} fy={} must be positive", c.fx, c.fy);
  const auto keyFrameIndex = indexById(problem.keyFrames, "keyframe");
  const auto pointIndex = indexById(problem.points, "point");
  std::vector<ObservationIndex> resolved;
  resolved.reserve(problem.observations.size());
  for (std::size_t i = 0; i < problem.observations.size(); ++i) {
    const BAObservation& obs = problem.observations[i];
    const auto kf = keyFrameIndex.find(obs.keyFrameId);
    if (kf == keyFrameIndex.end())
      fail("local BA: observation {} refers to unknown keyframe id {}", i, obs.keyFrameId);
    const auto point = pointIndex.find(obs.pointId);
    if (point == pointIndex.end())
      fail("local BA: observation {} refers to unknown point id {}", i, obs.pointId);
    if (!(obs.invSigma2 > 0.0) || !obs.uv.allFinite())
      fail("local BA: observation {} is invalid (invSigma2={}, uv=({}, {}))", i, obs.invSigma2,
           obs.uv.x(), obs.uv.y());
    if (obs.isStereo() && !(c.bf > 0.0))
      fail("local BA: observation {} is stereo but camera bf={} is not positive", i, c.bf);
    resolved.push_back({kf->second, point->second});
  }
  return resolved;
}

ceres::LinearSolverType linearSolverOf(SchurSolver solver) {
  switch (solver) {
    case SchurSolver::kSparse:
      return ceres::SPARSE_SCHUR;
    case SchurSolver::kIterative:
      return ceres::ITERATIVE_SCHUR;
    case SchurSolver::kDense:
      return ceres::DENSE_SCHUR;
  }
  return ceres::SPARSE_SCHUR;
}

ceres::Problem::Options nonOwningProblemOptions() {
  ceres::Problem::Options problemOptions;
  problemOptions.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problemOptions.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return problemOptions;
}

ceres::Solver::Options solverOptionsOf(const LocalBAOptions& options,
                                       std::shared_ptr<ceres::ParameterBlockOrdering> ordering) {
  ceres::Solver::Options solverOptions;
  solverOptions.linear_solver_type = linearSolverOf(options.solver);
  solverOptions.linear_solver_ordering = std::move(ordering);
  solverOptions.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  solverOptions.preconditioner_type = ceres::SCHUR_JACOBI;
  solverOptions.max_num_iterations = options.maxIterations;
  solverOptions.max_solver_time_in_seconds = options.maxSolverTimeSeconds;
  solverOptions.num_threads = 1;
  solverOptions.logging_type = ceres::SILENT;
  return solverOptions;
}

// summary.iterations includes the initial evaluation (iteration 0).
int iterationsOf(const ceres::Solver::Summary& summary) {
  return std::max(0, static_cast<int>(summary.iterations.size()) - 1);
}

// One adjustment: the pose and point blocks, the Ceres problem over them and the result.
class LocalBundle {
 public:
  LocalBundle(const LocalBAProblem& problem, const LocalBAOptions& options)
      : problem_(problem),
        options_(options),
        resolved_(resolveObservations(problem)),
        lossMono_(new ceres::HuberLoss(options.thresholds.huberDeltaMono()), ceres::TAKE_OWNERSHIP),
        lossStereo_(new ceres::HuberLoss(options.thresholds.huberDeltaStereo()),
                    ceres::TAKE_OWNERSHIP),
        ceresProblem_(nonOwningProblemOptions()),
        ordering_(std::make_shared<ceres::ParameterBlockOrdering>()) {
    poses_.reserve(problem.keyFrames.size());
    for (const BAKeyFrame& kf : problem.keyFrames) poses_.push_back(toPoseBlock(kf.T_c_w));
    points_.reserve(problem.points.size());
    for (const BAPoint& p : problem.points) points_.push_back(p.X_w);
    result_.isOutlier.assign(problem.observations.size(), false);
  }

  LocalBAResult& result() { return result_; }
  LocalBAResult takeResult() { return std::move(result_); }
  const std::shared_ptr<ceres::ParameterBlockOrdering>& ordering() const { return ordering_; }
  bool hasResiduals() const { return ceresProblem_.NumResidualBlocks() > 0; }

  void fillResult() {
    result_.T_c_w.clear();
    for (std::size_t k = 0; k < poses_.size(); ++k)
      result_.T_c_w.push_back(problem_.keyFrames[k].fixed ? problem_.keyFrames[k].T_c_w
                                                          : fromPoseBlock(poses_[k].data()));
    result_.X_w = points_;
  }

  void addParameterBlocks() {
    for (std::size_t k = 0; k < poses_.size(); ++k) {
      ceresProblem_.AddParameterBlock(poses_[k].data(), kPoseBlockSize, se3LeftManifold());
      if (problem_.keyFrames[k].fixed) ceresProblem_.SetParameterBlockConstant(poses_[k].data());
      ordering_->AddElementToGroup(poses_[k].data(), 1);
    }
    for (Eigen::Vector3d& point : points_) {
      ceresProblem_.AddParameterBlock(point.data(), 3);
      ordering_->AddElementToGroup(point.data(), 0);  // eliminated first (Schur)
    }
  }

  void addResiduals() {
    const auto& observations = problem_.observations;
    monoCosts_.assign(observations.size(), nullptr);
    stereoCosts_.assign(observations.size(), nullptr);
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const BAObservation& obs = observations[i];
      double* pose = poses_[resolved_[i].keyFrame].data();
      double* point = points_[resolved_[i].point].data();
      // Skip observations that cannot be projected at the start; they are classified below.
      if (!((fromPoseBlock(pose) * points_[resolved_[i].point]).z() > kMinProjectionDepth))
        continue;
      if (obs.isStereo()) {
        stereoCosts_[i] = new BundleReprojectionCost<3>(
            problem_.camera, {obs.uv.x(), obs.uv.y(), obs.uRight}, obs.invSigma2);
        ceresProblem_.AddResidualBlock(stereoCosts_[i], &lossStereo_, pose, point);
      } else {
        monoCosts_[i] = new BundleReprojectionCost<2>(problem_.camera, obs.uv, obs.invSigma2);
        ceresProblem_.AddResidualBlock(monoCosts_[i], &lossMono_, pose, point);
      }
    }
  }

  // Points without any active observation would make the system singular: hold them fixed.
  void fixUnobservedPoints() {
    std::vector<int> active(points_.size(), 0);
    for (std::size_t i = 0; i < problem_.observations.size(); ++i) {
      if ((monoCosts_[i] || stereoCosts_[i]) && !result_.isOutlier[i]) ++active[resolved_[i].point];
    }
    for (std::size_t j = 0; j < points_.size(); ++j) {
      if (active[j] == 0) ceresProblem_.SetParameterBlockConstant(points_[j].data());
    }
  }

  void classify() {
    fillResult();
    result_.numOutliers = 0;
    for (std::size_t i = 0; i < problem_.observations.size(); ++i) {
      const BAObservation& obs = problem_.observations[i];
      const Eigen::Vector3d P_c =
          result_.T_c_w[resolved_[i].keyFrame] * result_.X_w[resolved_[i].point];
      const double chi2 =
          obs.isStereo() ? reprojectionChi2<3>(problem_.camera, P_c,
                                               {obs.uv.x(), obs.uv.y(), obs.uRight}, obs.invSigma2)
                         : reprojectionChi2<2>(problem_.camera, P_c, obs.uv, obs.invSigma2);
      const double threshold =
          obs.isStereo() ? options_.thresholds.chi2Stereo : options_.thresholds.chi2Mono;
      result_.isOutlier[i] = !(chi2 <= threshold);
      if (result_.isOutlier[i]) ++result_.numOutliers;
    }
  }

  ceres::Solver::Summary solve(const ceres::Solver::Options& solverOptions) {
    ceres::Solver::Summary summary;
    ceres::Solve(solverOptions, &ceresProblem_, &summary);
    return summary;
  }

  // ORB-SLAM2's second stage: without the outliers, without the robust kernel.
  void dropOutliersAndKernels() {
    for (std::size_t i = 0; i < problem_.observations.size(); ++i) {
      if (monoCosts_[i]) monoCosts_[i]->setEnabled(!result_.isOutlier[i]);
      if (stereoCosts_[i]) stereoCosts_[i]->setEnabled(!result_.isOutlier[i]);
    }
    fixUnobservedPoints();
    lossMono_.Reset(nullptr, ceres::TAKE_OWNERSHIP);
    lossStereo_.Reset(nullptr, ceres::TAKE_OWNERSHIP);
  }

 private:
  const LocalBAProblem& problem_;
  const LocalBAOptions& options_;
  std::vector<ObservationIndex> resolved_;
  std::vector<PoseBlock> poses_;
  std::vector<Eigen::Vector3d> points_;
  LocalBAResult result_;
  ceres::LossFunctionWrapper lossMono_;
  ceres::LossFunctionWrapper lossStereo_;
  ceres::Problem ceresProblem_;
  std::shared_ptr<ceres::ParameterBlockOrdering> ordering_;
  // Non-owning: the problem owns the costs; the refinement stage disables the outliers'.
  std::vector<BundleReprojectionCost<2>*> monoCosts_;
  std::vector<BundleReprojectionCost<3>*> stereoCosts_;
};

}  // namespace

LocalBAResult optimizeLocalBundle(const LocalBAProblem& problem, const LocalBAOptions& options) {
  LocalBundle bundle(problem, options);
  LocalBAResult& result = bundle.result();
  if (options.abort && options.abort->load()) {
    result.aborted = true;
    bundle.fillResult();
    return bundle.takeResult();
  }
  bundle.addParameterBlocks();
  bundle.addResiduals();
  if (!bundle.hasResiduals()) {
    bundle.classify();
    return bundle.takeResult();
  }
  bundle.fixUnobservedPoints();

  ceres::Solver::Options solverOptions = solverOptionsOf(options, bundle.ordering());
  std::unique_ptr<AbortCallback> abortCallback;
  if (options.abort) {
    abortCallback = std::make_unique<AbortCallback>(options.abort);
    solverOptions.callbacks.push_back(abortCallback.get());
  }
  const auto aborted = [&] { return abortCallback && abortCallback->aborted(); };

  const ceres::Solver::Summary summary = bundle.solve(solverOptions);
  result.iterations = iterationsOf(summary);
  result.initialCost = summary.initial_cost;
  result.finalCost = summary.final_cost;
  result.aborted = aborted();
  bundle.classify();

  const double timeLeft = options.maxSolverTimeSeconds - summary.total_time_in_seconds;
  if (options.refinementIterations > 0 && !result.aborted && timeLeft > 0.0) {
    bundle.dropOutliersAndKernels();
    solverOptions.max_num_iterations = options.refinementIterations;
    solverOptions.max_solver_time_in_seconds = timeLeft;
    result.iterations += iterationsOf(bundle.solve(solverOptions));
    result.aborted = aborted();
    bundle.classify();
  }
  return bundle.takeResult();
}

}  // namespace lumaslam::optimize
