#include "lumaslam/loop/map_merge.h"

#include <algorithm>
#include <unordered_set>

namespace lumaslam::loop {

using optimize::Sim3;

MapMerge mergeFor(const LoopMatch& match) {
  const map::MapId current_map = match.current->mapId();
  const map::MapId loop_map = match.loop->mapId();
  MapMerge merge;
  merge.moved = std::max(current_map, loop_map);
  merge.into = std::min(current_map, loop_map);
  if (current_map == merge.moved) {
    // The current keyframe's world is the moved one: S = T_w_c(moved) * S_c_w(into).
    merge.S_wmoved_winto = Sim3::fromSE3(match.current->T_w_c()) * match.S_c_w;
  } else {
    // The loop keyframe's world is the moved one: S = S_c_w(moved)^-1 * T_c_w(into).
    merge.S_wmoved_winto = match.S_c_w.inverse() * Sim3::fromSE3(match.current->T_c_w());
  }
  return merge;
}

void moveMapInto(map::Map& map, const MapMerge& merge) {
  const Sim3 S_winto_wmoved = merge.S_wmoved_winto.inverse();
  std::unordered_set<map::Id> moved_points;
  for (const auto& keyframe : map.keyFramesOf(merge.moved)) {
    for (const auto& point : keyframe->mapPoints()) {
      if (!point || point->isBad() || !moved_points.insert(point->id()).second) continue;
      point->setPosition(S_winto_wmoved * point->position());
    }
    // S_c_winto = T_c_wmoved * S_wmoved_winto; the rigid pose divides the scale out.
    keyframe->setPose((Sim3::fromSE3(keyframe->T_c_w()) * merge.S_wmoved_winto).toSE3());
  }
  for (const auto& keyframe : map.keyFramesOf(merge.moved)) {
    for (const auto& point : keyframe->mapPoints()) {
      if (point && !point->isBad()) point->updateNormalAndDepth();
    }
  }
  map.relabelMap(merge.moved, merge.into);
}

}  // namespace lumaslam::loop
