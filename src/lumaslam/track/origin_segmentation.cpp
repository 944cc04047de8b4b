#include "lumaslam/track/origin_segmentation.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_set>

#include <spdlog/spdlog.h>
#include <Eigen/Geometry>

namespace lumaslam::track {
namespace {

// A matched point as the origin keyframe measured it and as the current frame measures it.
struct OriginPair {
  std::size_t feature = 0;
  std::shared_ptr<map::MapPoint> point;
  Eigen::Vector3d in_origin;
  Eigen::Vector3d in_current;
  double depth_tolerance = 0.0;    // along the current ray, metres
  double lateral_tolerance = 0.0;  // across it: a few pixels at the point's depth
};

Eigen::Vector3d unproject(const map::FeatureSet& features, std::size_t j,
                          const CameraIntrinsics& k) {
  const auto& p = features.undistorted[j];
  const double z = features.depth[j];
  return {(p.x - k.cx) * z / k.fx, (p.y - k.cy) * z / k.fy, z};
}

std::optional<std::size_t> indexInOrigin(const map::MapPoint& point, const map::KeyFrame& origin) {
  for (const auto& [keyframe, index] : point.observations()) {
    if (keyframe.get() == &origin && index >= 0) return static_cast<std::size_t>(index);
  }
  return std::nullopt;
}

std::vector<OriginPair> pairsWithOrigin(const Frame& current, const map::KeyFrame& origin,
                                        const CameraIntrinsics& k,
                                        const OriginSegmentationParams& params) {
  const auto& seen = origin.features();
  std::vector<OriginPair> pairs;
  for (std::size_t i = 0; i < current.size(); ++i) {
    const auto& point = current.points[i];
    if (!point || point->isBad() || current.features->depth[i] <= 0.0F) continue;
    const auto j = indexInOrigin(*point, origin);
    if (!j || *j >= seen.size() || seen.depth[*j] <= 0.0F) continue;
    OriginPair pair;
    pair.feature = i;
    pair.point = point;
    pair.in_origin = unproject(seen, *j, k);
    pair.in_current = current.unprojectCamera(i, k);
    const double s0 = params.depth_noise * pair.in_origin.z() * pair.in_origin.z();
    const double s1 = params.depth_noise * pair.in_current.z() * pair.in_current.z();
    pair.depth_tolerance =
        std::max(params.min_tolerance_m, params.tolerance_sigmas * std::sqrt(s0 * s0 + s1 * s1));
    const double level_scale =
        std::pow(1.2, std::max(0, current.features->keypoints[i].octave));  // ORB's 1.2
    pair.lateral_tolerance = params.lateral_tolerance_px * level_scale * pair.in_current.z() / k.fx;
    pairs.push_back(pair);
  }
  return pairs;
}

using Motion = Eigen::Isometry3d;  // origin camera -> current camera

std::optional<Motion> motionOf(const std::vector<OriginPair>& pairs,
                               const std::vector<std::size_t>& use) {
  if (use.size() < 3) return std::nullopt;
  Eigen::Matrix3Xd from(3, static_cast<Eigen::Index>(use.size()));
  Eigen::Matrix3Xd to(3, static_cast<Eigen::Index>(use.size()));
  for (std::size_t c = 0; c < use.size(); ++c) {
    from.col(static_cast<Eigen::Index>(c)) = pairs[use[c]].in_origin;
    to.col(static_cast<Eigen::Index>(c)) = pairs[use[c]].in_current;
  }
  const Eigen::Matrix4d m = Eigen::umeyama(from, to, false);
  if (!m.allFinite()) return std::nullopt;
  return Motion(m);
}

// Depth readings are coarse along the ray, pixels fine across it: a mover that slides
// sideways by a centimetre is caught at once.
bool fits(const OriginPair& pair, const Motion& motion) {
  const Eigen::Vector3d error = motion * pair.in_origin - pair.in_current;
  const Eigen::Vector3d ray = pair.in_current.normalized();
  const double along = error.dot(ray);
  const double across = (error - along * ray).norm();
  return std::abs(along) < pair.depth_tolerance && across < pair.lateral_tolerance;
}

std::vector<std::size_t> inliersOf(const std::vector<OriginPair>& pairs, const Motion& motion,
                                   const std::vector<bool>& available) {
  std::vector<std::size_t> inliers;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (!available[p]) continue;
    if (fits(pairs[p], motion)) {
      inliers.push_back(p);
    }
  }
  return inliers;
}

struct FoundMotion {
  Motion motion = Motion::Identity();
  std::vector<std::size_t> inliers;  // among the available pairs
};

// The rigid motion most of the available pairs share (RANSAC over 3-point samples, refitted on
// its inliers). Seeded: a sequential run repeats.
std::optional<FoundMotion> dominantMotion(const std::vector<OriginPair>& pairs,
                                          const std::vector<bool>& available,
                                          const OriginSegmentationParams& params) {
  std::vector<std::size_t> candidates;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (available[p]) candidates.push_back(p);
  }
  if (candidates.size() < 3) return std::nullopt;
  std::optional<FoundMotion> best;
  std::mt19937 random(12345U + static_cast<unsigned>(candidates.size()));
  std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
  for (int it = 0; it < params.iterations; ++it) {
    const std::vector<std::size_t> sample{candidates[pick(random)], candidates[pick(random)],
                                          candidates[pick(random)]};
    if (sample[0] == sample[1] || sample[1] == sample[2] || sample[0] == sample[2]) continue;
    const auto motion = motionOf(pairs, sample);
    if (!motion) continue;
    auto inliers = inliersOf(pairs, *motion, available);
    if (!best || inliers.size() > best->inliers.size())
      best = FoundMotion{*motion, std::move(inliers)};
  }
  if (!best) return best;
  if (const auto refit = motionOf(pairs, best->inliers)) {
    auto inliers = inliersOf(pairs, *refit, available);
    if (inliers.size() >= best->inliers.size()) *best = FoundMotion{*refit, std::move(inliers)};
  }
  return best;
}

// Of `members`, those that do not fit `other`.
std::vector<std::size_t> notFitting(const std::vector<OriginPair>& pairs,
                                    const std::vector<std::size_t>& members, const Motion& other) {
  std::vector<std::size_t> kept;
  for (const std::size_t p : members) {
    if (!fits(pairs[p], other)) kept.push_back(p);
  }
  return kept;
}

int coveredCells(const Frame& current, const std::vector<OriginPair>& pairs,
                 const std::vector<std::size_t>& members, int width, int height, int cell_px) {
  const int cell = std::max(8, cell_px);
  const int columns = (width + cell - 1) / cell;
  const int rows = (height + cell - 1) / cell;
  std::unordered_set<int> cells;
  for (const std::size_t p : members) {
    const auto& uv = current.features->undistorted[pairs[p].feature];
    const int c = std::clamp(static_cast<int>(uv.x) / cell, 0, columns - 1);
    const int r = std::clamp(static_cast<int>(uv.y) / cell, 0, rows - 1);
    cells.insert(r * columns + c);
  }
  return static_cast<int>(cells.size());
}

// A motion that follows a mover with a compensating turn also fits the far static scene: the
// two motions are told apart by the points only each of them explains. The mover's are a
// compact region; the static scene's are spread over the image. Returns whether `first` is
// the static one; `second`'s inliers become those over all pairs.
bool firstIsStatic(const Frame& current, const std::vector<OriginPair>& pairs,
                   const FoundMotion& first, FoundMotion& second, int width, int height,
                   const OriginSegmentationParams& params) {
  second.inliers = inliersOf(pairs, second.motion, std::vector<bool>(pairs.size(), true));
  const auto only_first = notFitting(pairs, first.inliers, second.motion);
  const auto only_second = notFitting(pairs, second.inliers, first.motion);
  return coveredCells(current, pairs, only_first, width, height, params.cell_px) >=
         coveredCells(current, pairs, only_second, width, height, params.cell_px);
}

// Holds for the static motion's pairs; Broken for those only the other motion fits.
RigidVerdict verdictOf(std::size_t features, const std::vector<OriginPair>& pairs,
                       const FoundMotion& still, const FoundMotion* moved) {
  RigidVerdict verdict;
  verdict.per_feature.assign(features, Rigidity::Untested);
  for (const std::size_t p : still.inliers) verdict.per_feature[pairs[p].feature] = Rigidity::Holds;
  verdict.holds = static_cast<int>(still.inliers.size());
  if (!moved) return verdict;
  for (const std::size_t p : notFitting(pairs, moved->inliers, still.motion)) {
    verdict.per_feature[pairs[p].feature] = Rigidity::Broken;
    ++verdict.broken;
  }
  return verdict;
}

}  // namespace

OriginSegmentation segmentAgainstOrigin(const Frame& current, const map::KeyFrame& origin,
                                        const CameraIntrinsics& k, int image_width,
                                        int image_height, const OriginSegmentationParams& params) {
  OriginSegmentation result;
  const auto pairs = pairsWithOrigin(current, origin, k, params);
  result.pairs = static_cast<int>(pairs.size());
  if (pairs.size() < static_cast<std::size_t>(std::max(3, params.min_points))) return result;
  std::vector<bool> rest(pairs.size(), true);
  auto first = dominantMotion(pairs, rest, params);
  if (!first) return result;
  for (const std::size_t p : first->inliers) rest[p] = false;
  auto second = dominantMotion(pairs, rest, params);
  const auto min_mover = static_cast<std::size_t>(std::max(3, params.min_mover_points));
  if (second && second->inliers.size() < min_mover) second.reset();
  const bool first_static =
      !second || firstIsStatic(current, pairs, *first, *second, image_width, image_height, params);
  const FoundMotion& still = first_static ? *first : *second;
  const FoundMotion* moved = !second ? nullptr : first_static ? &*second : &*first;
  spdlog::debug("frame {}: origin pairs {}, static {}, other {}", current.index, pairs.size(),
                still.inliers.size(), moved ? moved->inliers.size() : 0);
  const bool enough = still.inliers.size() >= static_cast<std::size_t>(params.min_points) &&
                      static_cast<double>(still.inliers.size()) >=
                          params.min_static_fraction * static_cast<double>(pairs.size());
  if (enough) {
    result.T_current_origin = still.motion;
    result.static_matches.assign(current.size(), nullptr);
    for (const std::size_t p : still.inliers) {
      result.static_matches[pairs[p].feature] = pairs[p].point;
    }
  }
  if (enough || moved) result.verdict = verdictOf(current.size(), pairs, still, moved);
  return result;
}

}  // namespace lumaslam::track
