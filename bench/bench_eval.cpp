// Cost of evaluating a long trajectory: association, Umeyama alignment, ATE and RPE.
#include <benchmark/benchmark.h>

#include <cmath>

#include <Eigen/Geometry>

#include "lumaslam/eval/association.h"
#include "lumaslam/eval/evaluation.h"

namespace {

using lumaslam::StampedPose;
using lumaslam::Trajectory;

Trajectory circle(std::size_t poses, double time_offset) {
  Trajectory trajectory;
  for (std::size_t i = 0; i < poses; ++i) {
    const double t = 0.01 * static_cast<double>(i);
    StampedPose pose;
    pose.timestamp = t + time_offset;
    pose.T_w_c.translation() = Eigen::Vector3d(std::cos(t), std::sin(t), 0.01 * t);
    pose.T_w_c.linear() = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    trajectory.push_back(pose);
  }
  return trajectory;
}

void BM_EvalAssociate(benchmark::State& state) {
  const auto poses = static_cast<std::size_t>(state.range(0));
  const Trajectory ground_truth = circle(poses, 0.0);
  const Trajectory estimate = circle(poses, 0.002);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lumaslam::eval::associate(estimate, ground_truth, 0.02));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_EvalAssociate)->Arg(1000)->Arg(10000);

void BM_EvalFullReport(benchmark::State& state) {
  const auto poses = static_cast<std::size_t>(state.range(0));
  const Trajectory ground_truth = circle(poses, 0.0);
  const Trajectory estimate = circle(poses, 0.002);
  lumaslam::eval::EvaluationOptions options;
  options.align = lumaslam::eval::AlignMode::Sim3;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lumaslam::eval::evaluate(estimate, ground_truth, options));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_EvalFullReport)->Arg(1000)->Arg(10000);

}  // namespace
