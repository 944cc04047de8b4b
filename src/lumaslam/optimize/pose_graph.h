#pragma once
// Pose graph (essential graph) optimisation for loop closing, as ORB-SLAM's
// OptimizeEssentialGraph: vertices are keyframe poses, edges relative-pose measurements
// (spanning tree, strong covisibility, loop edges) with information weights.
//  - optimizePoseGraph: SE3 vertices (stereo / RGB-D, scale observable).
//  - optimizeSim3PoseGraph: Sim3 vertices (monocular, corrects scale drift too).
// Edge error (i = from, j = to): E = Z_ij^-1 * (X_i_w * X_j_w^-1), residual
// r = L [2 vec(q_E); t_E (; log s_E)], with L^T L = information. The residual is ordered
// (rotation, translation[, log-scale]); the information matrix uses the same order.
// Vertices are parameterised as quaternion (ceres::EigenQuaternionManifold) + translation
// (+ log-scale for Sim3), with automatic differentiation: this runs once per loop closure,
// not per frame.
#include <atomic>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/core/pose.h"
#include "lumaslam/optimize/sim3.h"

namespace lumaslam::optimize {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix7d = Eigen::Matrix<double, 7, 7>;

struct PoseGraphOptions {
  int maxIterations = 20;
  const std::atomic<bool>* abort = nullptr;  // checked after every iteration
};

struct PoseGraphVertex {
  std::uint64_t id = 0;
  SE3 T_c_w = SE3::Identity();
  bool fixed = false;  // e.g. the loop keyframe, or the map's first keyframe
};

struct PoseGraphEdge {
  std::uint64_t fromId = 0;     // i
  std::uint64_t toId = 0;       // j
  SE3 T_i_j = SE3::Identity();  // measured T_i_w * T_j_w^-1 (camera j into camera i)
  Matrix6d information = Matrix6d::Identity();
};

struct PoseGraphProblem {
  std::vector<PoseGraphVertex> vertices{};
  std::vector<PoseGraphEdge> edges{};
};

struct PoseGraphResult {
  std::vector<SE3> T_c_w{};  // per vertex, input order
  int iterations = 0;
  bool aborted = false;
  double initialCost = 0.0;
  double finalCost = 0.0;
};

struct Sim3PoseGraphVertex {
  std::uint64_t id = 0;
  Sim3 S_c_w{};
  bool fixed = false;
};

struct Sim3PoseGraphEdge {
  std::uint64_t fromId = 0;
  std::uint64_t toId = 0;
  Sim3 S_i_j{};  // measured S_i_w * S_j_w^-1
  Matrix7d information = Matrix7d::Identity();
};

struct Sim3PoseGraphProblem {
  std::vector<Sim3PoseGraphVertex> vertices{};
  std::vector<Sim3PoseGraphEdge> edges{};
};

struct Sim3PoseGraphResult {
  std::vector<Sim3> S_c_w{};  // per vertex, input order; toSE3() gives the corrected T_c_w
  int iterations = 0;
  bool aborted = false;
  double initialCost = 0.0;
  double finalCost = 0.0;
};

// Both throw lumaslam::Error for duplicate vertex ids, edges to unknown vertices, a
// self-edge, an information matrix that is not symmetric positive definite, or a
// non-positive scale.
PoseGraphResult optimizePoseGraph(const PoseGraphProblem& problem,
                                  const PoseGraphOptions& options = {});
Sim3PoseGraphResult optimizeSim3PoseGraph(const Sim3PoseGraphProblem& problem,
                                          const PoseGraphOptions& options = {});

}  // namespace lumaslam::optimize
