// Pose graph optimisation on a loop of 24 keyframes around a 4 m circle with drifting
// odometry: with a loop edge the optimisation pulls the end of the loop back, without it the
// (self-consistent) odometry chain stays as it is. SE3 (stereo/RGB-D) and Sim3 (monocular,
// scale drift) variants.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/optimize/pose_graph.h"
#include "lumaslam/optimize/se3_parameter.h"

namespace lumaslam::optimize {
namespace {

constexpr int kNumPoses = 24;

// Ground truth T_c_w: cameras on a circle of radius 2 m, looking outwards.
std::vector<SE3> circleTrajectory() {
  std::vector<SE3> poses;
  for (int k = 0; k < kNumPoses; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / kNumPoses;
    SE3 T_w_c = SE3::Identity();
    T_w_c.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T_w_c.translation() =
        Eigen::Vector3d(2.0 * std::cos(angle), 0.1 * std::sin(3 * angle), 2.0 * std::sin(angle));
    poses.push_back(T_w_c.inverse());
  }
  return poses;
}

// Odometry T_i_(i+1) with a systematic yaw bias and a bit of noise.
SE3 driftedOdometry(const SE3& T_i_w, const SE3& T_j_w, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.002);
  SE3 bias = SE3::Identity();
  bias.linear() =
      expSO3(Eigen::Vector3d(noise(rng), 0.01 + noise(rng), noise(rng))).toRotationMatrix();
  bias.translation() = Eigen::Vector3d(0.01 + noise(rng), noise(rng), noise(rng));
  return bias * (T_i_w * T_j_w.inverse());
}

double centreError(const SE3& T_c_w, const SE3& truth) {
  return (T_c_w.inverse().translation() - truth.inverse().translation()).norm();
}

struct DriftedLoop {
  std::vector<SE3> truth;
  PoseGraphProblem problem;
};

DriftedLoop makeDriftedLoop(bool withLoopEdge) {
  DriftedLoop loop{circleTrajectory(), {}};
  std::mt19937 rng(5);
  SE3 T_c_w = loop.truth[0];
  for (int k = 0; k < kNumPoses; ++k) {
    if (k > 0) {
      const SE3 T_prev_k = driftedOdometry(loop.truth[k - 1], loop.truth[k], rng);
      loop.problem.edges.push_back(
          {.fromId = std::uint64_t(k - 1), .toId = std::uint64_t(k), .T_i_j = T_prev_k});
      T_c_w = T_prev_k.inverse() * T_c_w;  // chain: T_k_w = T_k_prev * T_prev_w
    }
    loop.problem.vertices.push_back({.id = std::uint64_t(k), .T_c_w = T_c_w, .fixed = k == 0});
  }
  if (withLoopEdge) {
    // Loop closure: the last keyframe re-observes the first, measured precisely.
    loop.problem.edges.push_back({.fromId = kNumPoses - 1,
                                  .toId = 0,
                                  .T_i_j = loop.truth.back() * loop.truth.front().inverse(),
                                  .information = 100.0 * Matrix6d::Identity()});
  }
  return loop;
}

TEST(OptimizePoseGraph, LoopEdgeRemovesDrift) {
  const DriftedLoop loop = makeDriftedLoop(true);
  const double endErrorBefore = centreError(loop.problem.vertices.back().T_c_w, loop.truth.back());
  ASSERT_GT(endErrorBefore, 0.3);
  const PoseGraphResult result = optimizePoseGraph(loop.problem);
  ASSERT_EQ(result.T_c_w.size(), loop.truth.size());
  const double endErrorAfter = centreError(result.T_c_w.back(), loop.truth.back());
  EXPECT_LT(endErrorAfter, 0.1 * endErrorBefore) << endErrorBefore << " -> " << endErrorAfter;
  double sumBefore = 0.0, sumAfter = 0.0;
  for (int k = 0; k < kNumPoses; ++k) {
    sumBefore += centreError(loop.problem.vertices[k].T_c_w, loop.truth[k]);
    sumAfter += centreError(result.T_c_w[k], loop.truth[k]);
  }
  EXPECT_LT(sumAfter, 0.3 * sumBefore);
  EXPECT_LT(result.finalCost, result.initialCost);
  EXPECT_TRUE(result.T_c_w.front().isApprox(loop.problem.vertices.front().T_c_w, 1e-12));
}

TEST(OptimizePoseGraph, WithoutLoopEdgeOdometryIsAlreadyOptimal) {
  const DriftedLoop loop = makeDriftedLoop(false);
  const PoseGraphResult result = optimizePoseGraph(loop.problem);
  for (int k = 0; k < kNumPoses; ++k)
    EXPECT_LT(centreError(result.T_c_w[k], loop.problem.vertices[k].T_c_w), 1e-6);
  EXPECT_NEAR(result.initialCost, 0.0, 1e-12);
}

TEST(OptimizePoseGraph, Sim3LoopEdgeCorrectsScaleDrift) {
  // Monocular drift as ORB-SLAM sees it at loop closure: the keyframe estimates (scale-1 Sim3
  // vertices) come from odometry whose map scale shrinks by 2% per keyframe (plus the yaw
  // bias), the essential-graph edges are their current relative poses, and the loop edge is
  // the Sim3 the loop detector measured: the true relative pose, in the last keyframe's map
  // scale s = 0.98^23.
  const std::vector<SE3> truth = circleTrajectory();
  Sim3PoseGraphProblem problem;
  std::mt19937 rng(8);
  std::vector<SE3> estimate{truth[0]};
  double mapScale = 1.0;
  for (int k = 1; k < kNumPoses; ++k) {
    mapScale *= 0.98;
    SE3 T_prev_k = driftedOdometry(truth[k - 1], truth[k], rng);
    T_prev_k.translation() *= mapScale;
    estimate.push_back(T_prev_k.inverse() * estimate.back());
  }
  for (int k = 0; k < kNumPoses; ++k) {
    problem.vertices.push_back(
        {.id = std::uint64_t(k), .S_c_w = Sim3::fromSE3(estimate[k]), .fixed = k == 0});
    if (k > 0) {
      problem.edges.push_back({.fromId = std::uint64_t(k - 1),
                               .toId = std::uint64_t(k),
                               .S_i_j = Sim3::fromSE3(estimate[k - 1] * estimate[k].inverse())});
    }
  }
  problem.edges.push_back({.fromId = kNumPoses - 1,
                           .toId = 0,
                           .S_i_j = Sim3::fromSE3(truth.back() * truth.front().inverse(), mapScale),
                           .information = 100.0 * Matrix7d::Identity()});

  const Sim3PoseGraphResult result = optimizeSim3PoseGraph(problem);
  ASSERT_EQ(result.S_c_w.size(), truth.size());
  const double endErrorBefore = centreError(estimate.back(), truth.back());
  const double endErrorAfter = centreError(result.S_c_w.back().toSE3(), truth.back());
  ASSERT_GT(endErrorBefore, 0.5);
  EXPECT_LT(endErrorAfter, 0.1 * endErrorBefore) << endErrorBefore << " -> " << endErrorAfter;
  EXPECT_NEAR(result.S_c_w.back().scale, mapScale, 0.05 * mapScale);
  double sumBefore = 0.0, sumAfter = 0.0;
  for (int k = 0; k < kNumPoses; ++k) {
    sumBefore += centreError(estimate[k], truth[k]);
    sumAfter += centreError(result.S_c_w[k].toSE3(), truth[k]);
  }
  EXPECT_LT(sumAfter, 0.5 * sumBefore) << sumBefore << " -> " << sumAfter;
  EXPECT_LT(result.finalCost, result.initialCost);
}

TEST(OptimizePoseGraph, Sim3ComposesAndInverts) {
  const Sim3 a{
      2.0, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())), {1.0, 2.0, 3.0}};
  const Sim3 b{
      0.5, Eigen::Quaterniond(Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ())), {-1.0, 0.0, 4.0}};
  const Eigen::Vector3d X(0.3, -0.7, 2.0);
  EXPECT_TRUE(((a * b) * X).isApprox(a * (b * X)));
  EXPECT_TRUE((a.inverse() * (a * X)).isApprox(X));
  const SE3 T = a.toSE3();
  EXPECT_TRUE((a * X).isApprox(2.0 * (T * X)));
}

TEST(OptimizePoseGraph, RejectsInconsistentInput) {
  DriftedLoop loop = makeDriftedLoop(true);
  PoseGraphProblem unknown = loop.problem;
  unknown.edges[3].toId = 777;
  EXPECT_THROW(optimizePoseGraph(unknown), Error);
  PoseGraphProblem duplicate = loop.problem;
  duplicate.vertices[2].id = 1;
  EXPECT_THROW(optimizePoseGraph(duplicate), Error);
  PoseGraphProblem badInformation = loop.problem;
  badInformation.edges[0].information(0, 0) = -1.0;
  const std::string message = test::errorOf([&] { optimizePoseGraph(badInformation); });
  EXPECT_NE(message.find("edge 0 information"), std::string::npos) << message;
  PoseGraphProblem selfEdge = loop.problem;
  selfEdge.edges[0].toId = selfEdge.edges[0].fromId;
  EXPECT_THROW(optimizePoseGraph(selfEdge), Error);
}

TEST(OptimizePoseGraph, PresetAbortLeavesPoses) {
  const DriftedLoop loop = makeDriftedLoop(true);
  const std::atomic<bool> abort{true};
  const PoseGraphResult result = optimizePoseGraph(loop.problem, {.abort = &abort});
  EXPECT_TRUE(result.aborted);
  for (int k = 0; k < kNumPoses; ++k)
    EXPECT_TRUE(result.T_c_w[k].isApprox(loop.problem.vertices[k].T_c_w, 1e-12));
}

}  // namespace
}  // namespace lumaslam::optimize
