#include "lumaslam/track/rigid_consensus.h"

#include <algorithm>
#include <cmath>

namespace lumaslam::track {
namespace {

// A matched point: where the map has it and where the current depth reading puts it.
struct PointPair {
  std::size_t feature = 0;
  Eigen::Vector3d in_map;
  Eigen::Vector3d in_frame;
  double sigma2 = 0.0;  // variance of its depth reading
};

std::vector<PointPair> matchedPointsWithDepth(const Frame& frame, const CameraIntrinsics& k,
                                              const RigidConsensusParams& params) {
  std::vector<PointPair> pairs;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto& point = frame.points[i];
    if (!point || point->isBad() || point->observationCount() < 1) continue;
    if (frame.features->depth[i] <= 0.0F) continue;
    PointPair pair;
    pair.feature = i;
    pair.in_map = point->position();
    pair.in_frame = frame.unprojectCamera(i, k);
    const double z = pair.in_frame.z();
    const double sigma = params.depth_noise * z * z;
    pair.sigma2 = sigma * sigma;
    pairs.push_back(pair);
  }
  return pairs;
}

bool distanceHolds(const PointPair& a, const PointPair& b, const RigidConsensusParams& params) {
  const double in_map = (a.in_map - b.in_map).norm();
  const double in_frame = (a.in_frame - b.in_frame).norm();
  const double tolerance =
      std::max(params.min_tolerance_m, params.tolerance_sigmas * std::sqrt(a.sigma2 + b.sigma2));
  return std::abs(in_map - in_frame) < tolerance;
}

// Row per anchor: which points keep their distance to it.
using HoldTable = std::vector<std::vector<bool>>;

HoldTable holdsWithAnchors(const std::vector<PointPair>& pairs,
                           const std::vector<std::size_t>& anchors,
                           const RigidConsensusParams& params) {
  HoldTable table(anchors.size(), std::vector<bool>(pairs.size(), false));
  for (std::size_t a = 0; a < anchors.size(); ++a) {
    for (std::size_t j = 0; j < pairs.size(); ++j) {
      table[a][j] = j == anchors[a] || distanceHolds(pairs[anchors[a]], pairs[j], params);
    }
  }
  return table;
}

// Anchors spread evenly over the points (deterministic: a sequential run repeats).
std::vector<std::size_t> pickAnchors(std::size_t points, int wanted) {
  const std::size_t n = std::min(points, static_cast<std::size_t>(std::max(1, wanted)));
  std::vector<std::size_t> anchors;
  for (std::size_t a = 0; a < n; ++a) anchors.push_back(a * points / n);
  return anchors;
}

// The anchors that speak for the static scene: the best supported one and those that agree
// with it and are supported nearly as well.
std::vector<std::size_t> voters(const HoldTable& table, const std::vector<std::size_t>& anchors,
                                const RigidConsensusParams& params) {
  std::vector<std::size_t> support(table.size());
  for (std::size_t a = 0; a < table.size(); ++a) {
    support[a] = static_cast<std::size_t>(std::count(table[a].begin(), table[a].end(), true));
  }
  const auto best =
      static_cast<std::size_t>(std::max_element(support.begin(), support.end()) - support.begin());
  std::vector<std::size_t> chosen;
  for (std::size_t a = 0; a < table.size(); ++a) {
    const bool agrees = table[best][anchors[a]];
    if (agrees && static_cast<double>(support[a]) >=
                      params.voter_support * static_cast<double>(support[best])) {
      chosen.push_back(a);
    }
  }
  return chosen;
}

}  // namespace

RigidVerdict rigidConsensus(const Frame& frame, const CameraIntrinsics& k,
                            const RigidConsensusParams& params) {
  RigidVerdict verdict;
  const auto pairs = matchedPointsWithDepth(frame, k, params);
  if (pairs.size() < static_cast<std::size_t>(std::max(2, params.min_points))) return verdict;
  const auto anchors = pickAnchors(pairs.size(), params.anchors);
  const auto table = holdsWithAnchors(pairs, anchors, params);
  const auto voting = voters(table, anchors, params);
  verdict.per_feature.assign(frame.size(), Rigidity::Untested);
  for (std::size_t j = 0; j < pairs.size(); ++j) {
    const auto agreeing =
        std::count_if(voting.begin(), voting.end(), [&](std::size_t a) { return table[a][j]; });
    const bool holds =
        static_cast<double>(agreeing) >= params.min_agreement * static_cast<double>(voting.size());
    verdict.per_feature[pairs[j].feature] = holds ? Rigidity::Holds : Rigidity::Broken;
    ++(holds ? verdict.holds : verdict.broken);
  }
  return verdict;
}

}  // namespace lumaslam::track
