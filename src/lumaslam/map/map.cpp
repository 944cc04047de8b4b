#include "lumaslam/map/map.h"

#include <algorithm>
#include <set>

namespace lumaslam::map {

void Map::addKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  {
    std::unique_lock lock(mutex_);
    if (keyframes_.empty() && origin_.expired()) origin_ = keyframe;
    origins_.try_emplace(keyframe->mapId(), keyframe->id());
    keyframes_[keyframe->id()] = keyframe;
  }
  // A reset map's keyframes (in a loaded map file) stay out of place recognition.
  if (index_ && keyframe->mapId() != kDiscardedMap) index_->add(keyframe);
}

Map::Bookkeeping Map::bookkeeping() const {
  std::shared_lock lock(mutex_);
  Bookkeeping result{next_keyframe_id_.load(), next_point_id_.load(), next_map_id_.load(),
                     {origins_.begin(), origins_.end()}};
  std::sort(result.origins.begin(), result.origins.end());
  return result;
}

void Map::restoreBookkeeping(const Bookkeeping& bookkeeping) {
  std::unique_lock lock(mutex_);
  next_keyframe_id_ = bookkeeping.next_keyframe_id;
  next_point_id_ = bookkeeping.next_point_id;
  next_map_id_ = bookkeeping.next_map_id;
  origins_ = {bookkeeping.origins.begin(), bookkeeping.origins.end()};
}

void Map::setKeyFrameIndex(std::shared_ptr<KeyFrameIndex> index) {
  index_ = std::move(index);
  if (!index_) return;
  index_->clear();
  for (const auto& keyframe : keyFrames()) {
    if (keyframe->mapId() != kDiscardedMap) index_->add(keyframe);
  }
}

void Map::addMapPoint(const std::shared_ptr<MapPoint>& point) {
  std::unique_lock lock(mutex_);
  points_[point->id()] = point;
}

std::shared_ptr<KeyFrame> Map::keyFrame(Id id) const {
  std::shared_lock lock(mutex_);
  const auto it = keyframes_.find(id);
  return it == keyframes_.end() ? nullptr : it->second;
}

std::shared_ptr<MapPoint> Map::mapPoint(Id id) const {
  std::shared_lock lock(mutex_);
  const auto it = points_.find(id);
  return it == points_.end() ? nullptr : it->second;
}

template <typename T>
static std::vector<std::shared_ptr<T>> sortedById(
    const std::unordered_map<Id, std::shared_ptr<T>>& objects) {
  std::vector<std::shared_ptr<T>> result;
  result.reserve(objects.size());
  for (const auto& [id, object] : objects) result.push_back(object);
  std::sort(result.begin(), result.end(),
            [](const auto& a, const auto& b) { return a->id() < b->id(); });
  return result;
}

std::vector<std::shared_ptr<KeyFrame>> Map::keyFrames() const {
  std::shared_lock lock(mutex_);
  return sortedById(keyframes_);
}

std::vector<std::shared_ptr<MapPoint>> Map::mapPoints() const {
  std::shared_lock lock(mutex_);
  return sortedById(points_);
}

std::size_t Map::keyFrameCount() const {
  std::shared_lock lock(mutex_);
  return keyframes_.size();
}

std::size_t Map::mapPointCount() const {
  std::shared_lock lock(mutex_);
  return points_.size();
}

std::shared_ptr<KeyFrame> Map::originKeyFrame() const {
  std::shared_lock lock(mutex_);
  return origin_.lock();
}

bool Map::isOrigin(const KeyFrame& keyframe) const {
  std::shared_lock lock(mutex_);
  return std::any_of(origins_.begin(), origins_.end(),
                     [&](const auto& entry) { return entry.second == keyframe.id(); });
}

bool Map::isMapOrigin(const KeyFrame& keyframe) const {
  std::shared_lock lock(mutex_);
  const auto it = origins_.find(keyframe.mapId());
  return it != origins_.end() && it->second == keyframe.id();
}

std::vector<std::shared_ptr<KeyFrame>> Map::keyFramesOf(MapId map) const {
  auto keyframes = keyFrames();
  std::erase_if(keyframes, [map](const auto& kf) { return kf->mapId() != map; });
  return keyframes;
}

std::size_t Map::keyFrameCountOf(MapId map) const {
  std::shared_lock lock(mutex_);
  return static_cast<std::size_t>(
      std::count_if(keyframes_.begin(), keyframes_.end(),
                    [map](const auto& entry) { return entry.second->mapId() == map; }));
}

void Map::relabelMap(MapId moved, MapId into) {
  std::unique_lock lock(mutex_);
  for (const auto& [id, keyframe] : keyframes_) {
    if (keyframe->mapId() == moved) keyframe->setMapId(into);
  }
}

void Map::discardMap(MapId map) {
  const auto discarded = keyFramesOf(map);
  relabelMap(map, kDiscardedMap);
  if (!index_) return;
  for (const auto& keyframe : discarded) index_->erase(keyframe->id());
}

void Map::retireMapPoint(const std::shared_ptr<MapPoint>& point) {
  if (!point) return;
  point->markBad();
  for (const auto& [keyframe, index] : point->observations()) {
    if (keyframe->mapPoint(static_cast<std::size_t>(index)) == point) {
      keyframe->eraseMapPoint(static_cast<std::size_t>(index));
    }
  }
  std::unique_lock lock(mutex_);
  points_.erase(point->id());
}

bool Map::retireKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  if (!keyframe || keyframe->isBad() || isOrigin(*keyframe)) return false;

  for (const auto& neighbour : keyframe->covisibles()) neighbour->eraseConnection(keyframe->id());
  for (const auto& point : keyframe->mapPoints()) {
    if (point && point->eraseObservation(keyframe->id())) retireMapPoint(point);
  }

  // Hand each child to the candidate it shares most points with; candidates start with our
  // parent and grow with every re-parented child (ORB-SLAM's SetBadFlag).
  const auto parent = keyframe->parent();
  auto children = keyframe->children();
  std::vector<std::shared_ptr<KeyFrame>> candidates;
  if (parent) candidates.push_back(parent);
  while (!children.empty()) {
    int best_weight = -1;
    std::size_t best_child = 0;
    std::shared_ptr<KeyFrame> best_parent;
    for (std::size_t c = 0; c < children.size(); ++c) {
      for (const auto& candidate : candidates) {
        const int w = children[c]->weight(candidate->id());
        if (w > best_weight && w > 0) {
          best_weight = w;
          best_child = c;
          best_parent = candidate;
        }
      }
    }
    if (!best_parent) break;
    children[best_child]->setParent(best_parent);
    best_parent->addChild(children[best_child]);
    candidates.push_back(children[best_child]);
    children.erase(children.begin() + static_cast<std::ptrdiff_t>(best_child));
  }
  for (const auto& child : children) {
    child->setParent(parent);
    if (parent) parent->addChild(child);
  }
  if (parent) parent->eraseChild(keyframe->id());

  keyframe->retire(parent);
  {
    std::unique_lock lock(mutex_);
    keyframes_.erase(keyframe->id());
  }
  if (index_) index_->erase(keyframe->id());
  return true;
}

void Map::replaceMapPoint(const std::shared_ptr<MapPoint>& old_point,
                          const std::shared_ptr<MapPoint>& new_point) {
  if (!old_point || !new_point || old_point == new_point) return;
  for (const auto& [keyframe, index] : old_point->observations()) {
    const auto slot = static_cast<std::size_t>(index);
    if (new_point->featureIndexIn(keyframe->id()) < 0) {
      keyframe->setMapPoint(slot, new_point);
      new_point->addObservation(keyframe, index);
    } else if (keyframe->mapPoint(slot) == old_point) {
      keyframe->eraseMapPoint(slot);
    }
  }
  old_point->setReplacement(new_point);
  old_point->markBad();
  new_point->computeDistinctiveDescriptor();
  std::unique_lock lock(mutex_);
  points_.erase(old_point->id());
}

void Map::clear() {
  {
    std::unique_lock lock(mutex_);
    keyframes_.clear();
    points_.clear();
    origin_.reset();
    origins_.clear();
    next_map_id_ = 1;
    next_keyframe_id_ = 0;
    next_point_id_ = 0;
  }
  if (index_) index_->clear();
}

}  // namespace lumaslam::map
