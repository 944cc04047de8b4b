#include "lumaslam/loop/relocalizer.h"

#include "lumaslam/core/error.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map_point.h"

namespace lumaslam::loop {

namespace {

std::vector<float> keypointAngles(const map::KeyFrame& keyframe) {
  std::vector<float> angles;
  angles.reserve(keyframe.features().size());
  for (const auto& kp : keyframe.features().keypoints) angles.push_back(kp.angle);
  return angles;
}

}  // namespace

Relocalizer::Relocalizer(const Vocabulary& vocabulary, const KeyFrameDatabase& database,
                         const map::Map& map, const RelocalizerParams& params)
    : vocabulary_(vocabulary), database_(database), map_(map), params_(params) {}

RelocalizationResult Relocalizer::relocalize(const RelocalizationFrame& frame) const {
  if (!frame.features || !frame.pyramid) fail("relocalization: frame without features/pyramid");
  if (!frame.features->grid) fail("relocalization: frame features without a FeatureGrid");
  RelocalizationResult result;
  const map::FeatureSet& features = *frame.features;
  result.points.assign(features.size(), nullptr);
  if (features.size() == 0 || vocabulary_.empty()) return result;

  BowVector bow;
  FeatureVector nodes;
  vocabulary_.transform(features.descriptors, params_.direct_index_levels_up, bow, nodes);
  PlaceQuery query;
  query.max_candidates = static_cast<std::size_t>(params_.max_candidates);
  const auto candidates = database_.query(bow, query);
  result.candidates = static_cast<int>(candidates.size());

  const PnpRansacParams pnp{params_.pnp_iterations, params_.pnp_reprojection_px,
                            params_.min_pnp_inliers};
  for (const auto& candidate : candidates) {
    const auto keyframe = map_.keyFrame(candidate.id);
    const auto entry = database_.entry(candidate.id);
    if (!keyframe || keyframe->isBad() || !entry) continue;
    PointSlots slots = searchByBow(*keyframe, entry->features, features, nodes, params_.bow_ratio,
                                   params_.bow_max_distance);
    if (countMatches(slots) < params_.min_bow_matches) continue;
    ++result.tried;
    SE3 T_c_w;
    if (!solvePnpRansac(frame, pnp, slots, T_c_w)) continue;
    int good = refinePose(frame, slots, T_c_w);
    if (good < params_.min_pnp_inliers) continue;
    // Too few inliers: look for more matches by projection and refine again (ORB-SLAM's
    // wide window 10 px / distance 100, then narrow 3 px / 64 with the better pose).
    if (good < params_.min_inliers) {
      const auto angles = keypointAngles(*keyframe);
      const int added = searchByProjection(frame, keyframe->mapPoints(), angles, T_c_w, 10.0F,
                                           feature::kThHigh, slots);
      if (good + added >= params_.min_inliers) {
        good = refinePose(frame, slots, T_c_w);
        if (good > 30 && good < params_.min_inliers) {
          const int more =
              searchByProjection(frame, keyframe->mapPoints(), angles, T_c_w, 3.0F, 64, slots);
          if (good + more >= params_.min_inliers) good = refinePose(frame, slots, T_c_w);
        }
      }
    }
    if (good < params_.min_inliers) continue;
    result.success = true;
    result.T_c_w = T_c_w;
    result.points = std::move(slots);
    result.inliers = good;
    result.keyframe = candidate.id;
    break;
  }
  return result;
}

}  // namespace lumaslam::loop
