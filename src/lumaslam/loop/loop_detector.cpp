#include "lumaslam/loop/loop_detector.h"

#include <algorithm>

#include "lumaslam/map/keyframe.h"

namespace lumaslam::loop {

LoopDetector::LoopDetector(const KeyFrameDatabase& database, const map::Map& map,
                           const LoopDetectorParams& params)
    : database_(database), map_(map), params_(params) {}

LoopDetection LoopDetector::detect(const std::shared_ptr<map::KeyFrame>& keyframe) {
  LoopDetection detection;
  const auto entry = database_.entry(keyframe->id());
  if (!entry) return detection;

  // 1. The score bar: the least similar covisible neighbour.
  const auto neighbours =
      params_.score_neighbours > 0
          ? keyframe->covisibles(static_cast<std::size_t>(params_.score_neighbours))
          : keyframe->covisiblesWithMinWeight(map::KeyFrame::kMinCovisibilityWeight);
  double min_score = 1.0;
  int scored = 0;
  for (const auto& neighbour : neighbours) {
    if (neighbour->isBad()) continue;
    const auto other = database_.entry(neighbour->id());
    if (!other) continue;
    min_score = std::min(min_score, score(entry->bow, other->bow));
    ++scored;
  }
  if (scored == 0) min_score = 0.0;

  // 2. Candidates above the bar, not connected to the keyframe.
  PlaceQuery query;
  query.min_score = min_score;
  query.excluded.insert(keyframe->id());
  for (const auto& connected : keyframe->covisibles()) query.excluded.insert(connected->id());
  const std::size_t group_size = static_cast<std::size_t>(params_.group_neighbours);
  query.neighbours = [this, group_size](KeyFrameId id) {
    std::vector<KeyFrameId> ids;
    if (const auto kf = map_.keyFrame(id)) {
      for (const auto& n : kf->covisibles(group_size)) ids.push_back(n->id());
    }
    return ids;
  };
  const auto candidates = database_.query(entry->bow, query);
  detection.candidates = static_cast<int>(candidates.size());

  // 3. Consistency with the groups of the previous keyframes.
  std::vector<ConsistentGroup> current_groups;
  std::vector<bool> group_extended(groups_.size(), false);
  for (const auto& candidate : candidates) {
    const auto candidate_kf = map_.keyFrame(candidate.id);
    if (!candidate_kf || candidate_kf->isBad()) continue;
    std::set<map::Id> group{candidate.id};
    for (const auto& n : candidate_kf->covisibles()) group.insert(n->id());

    bool enough = false;
    bool consistent_with_any = false;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const bool shares = std::any_of(group.begin(), group.end(), [&](map::Id id) {
        return groups_[g].keyframes.contains(id);
      });
      if (!shares) continue;
      consistent_with_any = true;
      const int consistency = groups_[g].consistency + 1;
      if (!group_extended[g]) {
        current_groups.push_back({group, consistency});
        group_extended[g] = true;
      }
      if (consistency >= params_.consistency_threshold && !enough) {
        detection.consistent.push_back(candidate_kf);
        enough = true;  // one accepted entry per candidate
      }
    }
    if (!consistent_with_any) current_groups.push_back({group, 0});
  }
  groups_ = std::move(current_groups);
  return detection;
}

}  // namespace lumaslam::loop
