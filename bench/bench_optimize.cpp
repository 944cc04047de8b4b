// Pose-only optimisation (per frame) and local bundle adjustment (per keyframe) on synthetic
// problems (optimize/synthetic_problems.h). Results: docs/optimization.md.
#include <benchmark/benchmark.h>

#include "lumaslam/optimize/local_ba.h"
#include "lumaslam/optimize/pose_only.h"
#include "lumaslam/optimize/synthetic_problems.h"

namespace {

using namespace lumaslam::optimize;

// Args: observations, stereo (0/1), variant (0: batched residuals + normal Cholesky, the
// default; 1: batched + DENSE_QR; 2: one residual block per observation + ceres::HuberLoss;
// 3: PoseBackend::kLevenbergMarquardt, the tracker's choice).
void BM_PoseOnly(benchmark::State& state) {
  const SyntheticPoseOnly synthetic =
      makeSyntheticPoseOnly({.numObservations = static_cast<int>(state.range(0)),
                             .stereo = state.range(1) != 0,
                             .noise = {.pyramidLevels = 8},
                             .seed = 3});
  PoseOnlyOptions options;
  options.solver = state.range(2) == 1 ? DenseSolver::kQR : DenseSolver::kNormalCholesky;
  options.batchResiduals = state.range(2) != 2;
  if (state.range(2) == 3) options.backend = PoseBackend::kLevenbergMarquardt;
  int inliers = 0;
  int iterations = 0;
  for (auto _ : state) {
    const PoseOnlyResult result = optimizePose(synthetic.problem, options);
    inliers = result.numInliers;
    iterations = result.iterations;
    benchmark::DoNotOptimize(result.T_c_w);
  }
  state.counters["inliers"] = inliers;
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_PoseOnly)
    ->ArgsProduct({{300, 1000}, {0, 1}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMicrosecond);

// Args: points, stereo (0/1), solver (0 sparse Schur, 1 iterative Schur, 2 dense Schur).
void BM_LocalBA(benchmark::State& state) {
  const SyntheticBundle scene = makeSyntheticBundle({.numKeyFrames = 10,
                                                     .numPoints = static_cast<int>(state.range(0)),
                                                     .stereo = state.range(1) != 0,
                                                     .seed = 3});
  const LocalBAOptions options{.solver = static_cast<SchurSolver>(state.range(2))};
  int iterations = 0;
  for (auto _ : state) {
    const LocalBAResult result = optimizeLocalBundle(scene.problem, options);
    iterations = result.iterations;
    benchmark::DoNotOptimize(result.T_c_w);
  }
  state.counters["observations"] = static_cast<double>(scene.problem.observations.size());
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_LocalBA)
    ->Args({2000, 0, 0})
    ->Args({2000, 0, 1})
    ->Args({2000, 0, 2})
    ->Args({2000, 1, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace
