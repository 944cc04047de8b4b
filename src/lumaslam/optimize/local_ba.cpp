#include "lumaslam/optimize/local_ba.h"

#include <algorithm>
#include <memory>
#include <unordered_map>

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

}  // namespace

LocalBAResult optimizeLocalBundle(const LocalBAProblem& problem, const LocalBAOptions& options) {
  const std::vector<ObservationIndex> resolved = resolveObservations(problem);
  const auto& observations = problem.observations;

  std::vector<PoseBlock> poses;
  poses.reserve(problem.keyFrames.size());
  for (const BAKeyFrame& kf : problem.keyFrames) poses.push_back(toPoseBlock(kf.T_c_w));
  std::vector<Eigen::Vector3d> points;
  points.reserve(problem.points.size());
  for (const BAPoint& p : problem.points) points.push_back(p.X_w);

  LocalBAResult result;
  const auto fillResult = [&] {
    result.T_c_w.clear();
    for (std::size_t k = 0; k < poses.size(); ++k)
      result.T_c_w.push_back(problem.keyFrames[k].fixed ? problem.keyFrames[k].T_c_w
                                                        : fromPoseBlock(poses[k].data()));
    result.X_w = points;
  };
  result.isOutlier.assign(observations.size(), false);
  if (options.abort && options.abort->load()) {
    result.aborted = true;
    fillResult();
    return result;
  }

  ceres::LossFunctionWrapper lossMono(new ceres::HuberLoss(options.thresholds.huberDeltaMono()),
                                      ceres::TAKE_OWNERSHIP);
  ceres::LossFunctionWrapper lossStereo(new ceres::HuberLoss(options.thresholds.huberDeltaStereo()),
                                        ceres::TAKE_OWNERSHIP);
  ceres::Problem::Options problemOptions;
  problemOptions.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problemOptions.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem ceresProblem(problemOptions);
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();

  for (std::size_t k = 0; k < poses.size(); ++k) {
    ceresProblem.AddParameterBlock(poses[k].data(), kPoseBlockSize, se3LeftManifold());
    if (problem.keyFrames[k].fixed) ceresProblem.SetParameterBlockConstant(poses[k].data());
    ordering->AddElementToGroup(poses[k].data(), 1);
  }
  for (Eigen::Vector3d& point : points) {
    ceresProblem.AddParameterBlock(point.data(), 3);
    ordering->AddElementToGroup(point.data(), 0);  // eliminated first (Schur)
  }
  // Non-owning: the problem owns the costs; the refinement stage disables the outliers'.
  std::vector<BundleReprojectionCost<2>*> monoCosts(observations.size(), nullptr);
  std::vector<BundleReprojectionCost<3>*> stereoCosts(observations.size(), nullptr);
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const BAObservation& obs = observations[i];
    double* pose = poses[resolved[i].keyFrame].data();
    double* point = points[resolved[i].point].data();
    // Skip observations that cannot be projected at the start; they are classified below.
    if (!((fromPoseBlock(pose) * points[resolved[i].point]).z() > kMinProjectionDepth)) continue;
    if (obs.isStereo()) {
      stereoCosts[i] = new BundleReprojectionCost<3>(
          problem.camera, {obs.uv.x(), obs.uv.y(), obs.uRight}, obs.invSigma2);
      ceresProblem.AddResidualBlock(stereoCosts[i], &lossStereo, pose, point);
    } else {
      monoCosts[i] = new BundleReprojectionCost<2>(problem.camera, obs.uv, obs.invSigma2);
      ceresProblem.AddResidualBlock(monoCosts[i], &lossMono, pose, point);
    }
  }
  // Points without any active observation would make the system singular: hold them fixed.
  const auto fixUnobservedPoints = [&] {
    std::vector<int> active(points.size(), 0);
    for (std::size_t i = 0; i < observations.size(); ++i) {
      if ((monoCosts[i] || stereoCosts[i]) && !result.isOutlier[i]) ++active[resolved[i].point];
    }
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (active[j] == 0) ceresProblem.SetParameterBlockConstant(points[j].data());
    }
  };
  const auto classify = [&] {
    fillResult();
    result.numOutliers = 0;
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const BAObservation& obs = observations[i];
      const Eigen::Vector3d P_c =
          result.T_c_w[resolved[i].keyFrame] * result.X_w[resolved[i].point];
      const double chi2 =
          obs.isStereo() ? reprojectionChi2<3>(problem.camera, P_c,
                                               {obs.uv.x(), obs.uv.y(), obs.uRight}, obs.invSigma2)
                         : reprojectionChi2<2>(problem.camera, P_c, obs.uv, obs.invSigma2);
      const double threshold =
          obs.isStereo() ? options.thresholds.chi2Stereo : options.thresholds.chi2Mono;
      result.isOutlier[i] = !(chi2 <= threshold);
      if (result.isOutlier[i]) ++result.numOutliers;
    }
  };
  if (ceresProblem.NumResidualBlocks() == 0) {
    classify();
    return result;
  }
  fixUnobservedPoints();

  ceres::Solver::Options solverOptions;
  solverOptions.linear_solver_type = linearSolverOf(options.solver);
  solverOptions.linear_solver_ordering = ordering;
  solverOptions.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  solverOptions.preconditioner_type = ceres::SCHUR_JACOBI;
  solverOptions.max_num_iterations = options.maxIterations;
  solverOptions.max_solver_time_in_seconds = options.maxSolverTimeSeconds;
  solverOptions.num_threads = 1;
  solverOptions.logging_type = ceres::SILENT;
  std::unique_ptr<AbortCallback> abortCallback;
  if (options.abort) {
    abortCallback = std::make_unique<AbortCallback>(options.abort);
    solverOptions.callbacks.push_back(abortCallback.get());
  }
  // summary.iterations includes the initial evaluation (iteration 0).
  const auto iterationsOf = [](const ceres::Solver::Summary& summary) {
    return std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  };

  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions, &ceresProblem, &summary);
  result.iterations = iterationsOf(summary);
  result.initialCost = summary.initial_cost;
  result.finalCost = summary.final_cost;
  result.aborted = abortCallback && abortCallback->aborted();
  classify();

  const double timeLeft = options.maxSolverTimeSeconds - summary.total_time_in_seconds;
  if (options.refinementIterations > 0 && !result.aborted && timeLeft > 0.0) {
    // ORB-SLAM2's second stage: without the outliers, without the robust kernel.
    for (std::size_t i = 0; i < observations.size(); ++i) {
      if (monoCosts[i]) monoCosts[i]->setEnabled(!result.isOutlier[i]);
      if (stereoCosts[i]) stereoCosts[i]->setEnabled(!result.isOutlier[i]);
    }
    fixUnobservedPoints();
    lossMono.Reset(nullptr, ceres::TAKE_OWNERSHIP);
    lossStereo.Reset(nullptr, ceres::TAKE_OWNERSHIP);
    solverOptions.max_num_iterations = options.refinementIterations;
    solverOptions.max_solver_time_in_seconds = timeLeft;
    ceres::Solver::Summary refinement;
    ceres::Solve(solverOptions, &ceresProblem, &refinement);
    result.iterations += iterationsOf(refinement);
    result.aborted = abortCallback && abortCallback->aborted();
    classify();
  }
  return result;
}

}  // namespace lumaslam::optimize
