#include "lumaslam/optimize/pose_graph.h"

#include <algorithm>
#include <memory>
#include <unordered_map>

#include <ceres/autodiff_cost_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"
#include "lumaslam/optimize/abort_callback.h"

namespace lumaslam::optimize {

namespace {

// One vertex's parameter blocks: quaternion (x, y, z, w), translation, log-scale.
struct VertexState {
  std::array<double, 4> q;
  std::array<double, 3> t;
  double logScale = 0.0;
};

VertexState stateOf(const Sim3& S) {
  const Eigen::Quaterniond q = S.rotation.normalized();
  return {{q.x(), q.y(), q.z(), q.w()},
          {S.translation.x(), S.translation.y(), S.translation.z()},
          std::log(S.scale)};
}

Sim3 sim3Of(const VertexState& state) {
  return {std::exp(state.logScale),
          Eigen::Quaterniond(state.q[3], state.q[0], state.q[1], state.q[2]).normalized(),
          Eigen::Vector3d(state.t[0], state.t[1], state.t[2])};
}

// r = L [2 vec(q_E); t_E; log s_E] for E = Z^-1 * (X_i * X_j^-1) (pose_graph.h); the first
// kResiduals rows (6: SE3, 7: Sim3).
template <int kResiduals>
struct RelativeSimilarityError {
  RelativeSimilarityError(const Sim3& measured,
                          const Eigen::Matrix<double, kResiduals, kResiduals>& sqrtInformation)
      : qMeasuredInverse(measured.rotation.conjugate().normalized()),
        tMeasured(measured.translation),
        logScaleMeasured(std::log(measured.scale)),
        sqrtInformation(sqrtInformation) {}

  template <typename T>
  bool evaluate(const T* q_i, const T* t_i, const T& logScale_i, const T* q_j, const T* t_j,
                const T& logScale_j, T* residual) const {
    using Quaternion = Eigen::Quaternion<T>;
    using Vector3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Quaternion> qi(q_i);
    const Eigen::Map<const Quaternion> qj(q_j);
    const Eigen::Map<const Vector3> ti(t_i);
    const Eigen::Map<const Vector3> tj(t_j);
    // X_i * X_j^-1 = (s_i / s_j, R_i R_j^T, t_i - (s_i / s_j) R_i R_j^T t_j).
    using std::exp;
    const T logScale_ij = logScale_i - logScale_j;
    const Quaternion q_ij = qi * qj.conjugate();
    const Vector3 t_ij = ti - exp(logScale_ij) * (q_ij * tj);
    // E = Z^-1 * X_ij = (s_ij / s_m, R_m^T R_ij, R_m^T (t_ij - t_m) / s_m).
    const Quaternion qm = qMeasuredInverse.template cast<T>();
    const Quaternion q_E = qm * q_ij;
    const Vector3 t_E =
        (qm * (t_ij - tMeasured.template cast<T>())) * T(std::exp(-logScaleMeasured));
    Eigen::Matrix<T, 7, 1> error;
    error << T(2.0) * q_E.vec(), t_E, logScale_ij - T(logScaleMeasured);
    Eigen::Map<Eigen::Matrix<T, kResiduals, 1>> r(residual);
    r = sqrtInformation.template cast<T>() * error.template head<kResiduals>();
    return true;
  }

  Eigen::Quaterniond qMeasuredInverse;
  Eigen::Vector3d tMeasured;
  double logScaleMeasured;
  Eigen::Matrix<double, kResiduals, kResiduals> sqrtInformation;
};

struct SE3EdgeError : RelativeSimilarityError<6> {
  using RelativeSimilarityError<6>::RelativeSimilarityError;
  template <typename T>
  bool operator()(const T* q_i, const T* t_i, const T* q_j, const T* t_j, T* residual) const {
    return evaluate(q_i, t_i, T(0.0), q_j, t_j, T(0.0), residual);
  }
};

struct Sim3EdgeError : RelativeSimilarityError<7> {
  using RelativeSimilarityError<7>::RelativeSimilarityError;
  template <typename T>
  bool operator()(const T* q_i, const T* t_i, const T* logScale_i, const T* q_j, const T* t_j,
                  const T* logScale_j, T* residual) const {
    return evaluate(q_i, t_i, *logScale_i, q_j, t_j, *logScale_j, residual);
  }
};

template <int N>
Eigen::Matrix<double, N, N> sqrtInformationOf(const Eigen::Matrix<double, N, N>& information,
                                              std::size_t edge) {
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(information);
  if (!information.allFinite() || !information.isApprox(information.transpose()) ||
      llt.info() != Eigen::Success)
    fail("pose graph: edge {} information matrix is not symmetric positive definite", edge);
  return llt.matrixU();  // U^T U = information
}

// Shared driver for both variants; `Vertex`/`Edge` expose id/fixed and fromId/toId.
template <bool kWithScale, typename Vertex, typename Edge>
struct GraphSolve {
  std::vector<VertexState> states;
  int iterations = 0;
  bool aborted = false;
  double initialCost = 0.0;
  double finalCost = 0.0;

  GraphSolve(const std::vector<Vertex>& vertices, const std::vector<Edge>& edges,
             const std::vector<Sim3>& initial, const std::vector<Sim3>& measured,
             const PoseGraphOptions& options) {
    std::unordered_map<std::uint64_t, int> indexById;
    for (int v = 0; v < static_cast<int>(vertices.size()); ++v) {
      if (!indexById.emplace(vertices[v].id, v).second)
        fail("pose graph: duplicate vertex id {}", vertices[v].id);
      if (!(initial[v].scale > 0.0))
        fail("pose graph: vertex id {} has scale {} (must be > 0)", vertices[v].id,
             initial[v].scale);
      states.push_back(stateOf(initial[v]));
    }
    if (options.abort && options.abort->load()) {
      aborted = true;
      return;
    }

    ceres::Problem::Options problemOptions;
    problemOptions.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problemOptions);
    ceres::EigenQuaternionManifold quaternionManifold;
    std::vector<int> edgesPerVertex(vertices.size(), 0);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const Edge& edge = edges[e];
      const auto from = indexById.find(edge.fromId);
      const auto to = indexById.find(edge.toId);
      if (from == indexById.end() || to == indexById.end())
        fail("pose graph: edge {} ({} -> {}) refers to an unknown vertex id", e, edge.fromId,
             edge.toId);
      if (from->second == to->second)
        fail("pose graph: edge {} joins vertex {} to itself", e, edge.fromId);
      if (!(measured[e].scale > 0.0))
        fail("pose graph: edge {} has scale {} (must be > 0)", e, measured[e].scale);
      VertexState& i = states[from->second];
      VertexState& j = states[to->second];
      ++edgesPerVertex[from->second];
      ++edgesPerVertex[to->second];
      if constexpr (kWithScale) {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<Sim3EdgeError, 7, 4, 3, 1, 4, 3, 1>(
                new Sim3EdgeError(measured[e], sqrtInformationOf<7>(edge.information, e))),
            nullptr, i.q.data(), i.t.data(), &i.logScale, j.q.data(), j.t.data(), &j.logScale);
      } else {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<SE3EdgeError, 6, 4, 3, 4, 3>(
                new SE3EdgeError(measured[e], sqrtInformationOf<6>(edge.information, e))),
            nullptr, i.q.data(), i.t.data(), j.q.data(), j.t.data());
      }
    }
    if (problem.NumResidualBlocks() == 0) return;

    const bool anyFixed =
        std::any_of(vertices.begin(), vertices.end(), [](const Vertex& v) { return v.fixed; });
    if (!anyFixed)
      spdlog::debug("pose graph: no fixed vertex, holding vertex {} fixed", vertices[0].id);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      if (edgesPerVertex[v] == 0) continue;  // not in the problem
      VertexState& state = states[v];
      problem.SetManifold(state.q.data(), &quaternionManifold);
      const bool fixed = vertices[v].fixed || (!anyFixed && v == 0);
      if (fixed) {
        problem.SetParameterBlockConstant(state.q.data());
        problem.SetParameterBlockConstant(state.t.data());
        if constexpr (kWithScale) problem.SetParameterBlockConstant(&state.logScale);
      }
    }

    ceres::Solver::Options solverOptions;
    solverOptions.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solverOptions.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
    solverOptions.max_num_iterations = options.maxIterations;
    solverOptions.num_threads = 1;
    solverOptions.logging_type = ceres::SILENT;
    AbortCallback abortCallback(options.abort);
    solverOptions.callbacks.push_back(&abortCallback);
    ceres::Solver::Summary summary;
    ceres::Solve(solverOptions, &problem, &summary);
    iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
    aborted = abortCallback.aborted();
    initialCost = summary.initial_cost;
    finalCost = summary.final_cost;
  }
};

}  // namespace

PoseGraphResult optimizePoseGraph(const PoseGraphProblem& problem,
                                  const PoseGraphOptions& options) {
  std::vector<Sim3> initial;
  for (const PoseGraphVertex& v : problem.vertices) initial.push_back(Sim3::fromSE3(v.T_c_w));
  std::vector<Sim3> measured;
  for (const PoseGraphEdge& e : problem.edges) measured.push_back(Sim3::fromSE3(e.T_i_j));
  const GraphSolve<false, PoseGraphVertex, PoseGraphEdge> solve(problem.vertices, problem.edges,
                                                                initial, measured, options);
  PoseGraphResult result;
  for (const VertexState& state : solve.states) result.T_c_w.push_back(sim3Of(state).toSE3());
  result.iterations = solve.iterations;
  result.aborted = solve.aborted;
  result.initialCost = solve.initialCost;
  result.finalCost = solve.finalCost;
  return result;
}

Sim3PoseGraphResult optimizeSim3PoseGraph(const Sim3PoseGraphProblem& problem,
                                          const PoseGraphOptions& options) {
  std::vector<Sim3> initial;
  for (const Sim3PoseGraphVertex& v : problem.vertices) initial.push_back(v.S_c_w);
  std::vector<Sim3> measured;
  for (const Sim3PoseGraphEdge& e : problem.edges) measured.push_back(e.S_i_j);
  const GraphSolve<true, Sim3PoseGraphVertex, Sim3PoseGraphEdge> solve(
      problem.vertices, problem.edges, initial, measured, options);
  Sim3PoseGraphResult result;
  for (const VertexState& state : solve.states) result.S_c_w.push_back(sim3Of(state));
  result.iterations = solve.iterations;
  result.aborted = solve.aborted;
  result.initialCost = solve.initialCost;
  result.finalCost = solve.finalCost;
  return result;
}

}  // namespace lumaslam::optimize
