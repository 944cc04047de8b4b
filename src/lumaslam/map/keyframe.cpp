#include "lumaslam/map/keyframe.h"

#include <algorithm>
#include <cstring>

#include "lumaslam/map/map_point.h"

namespace lumaslam::map {

KeyFrame::KeyFrame(Id id, std::size_t frame_index, double timestamp, const SE3& T_c_w,
                   std::shared_ptr<const FeatureSet> features,
                   std::shared_ptr<const feature::ScaleLevels> pyramid,
                   const CameraIntrinsics& intrinsics)
    : id_(id),
      frame_index_(frame_index),
      timestamp_(timestamp),
      features_(std::move(features)),
      pyramid_(std::move(pyramid)),
      intrinsics_(intrinsics),
      T_c_w_(T_c_w),
      T_w_c_(T_c_w.inverse()),
      points_(features_->size()) {}

Descriptor KeyFrame::descriptor(std::size_t feature_index) const {
  Descriptor d{};
  std::memcpy(d.data(), features_->descriptors.ptr<std::uint8_t>(static_cast<int>(feature_index)),
              d.size());
  return d;
}

SE3 KeyFrame::T_c_w() const {
  std::lock_guard lock(pose_mutex_);
  return T_c_w_;
}

SE3 KeyFrame::T_w_c() const {
  std::lock_guard lock(pose_mutex_);
  return T_w_c_;
}

Eigen::Vector3d KeyFrame::center() const {
  std::lock_guard lock(pose_mutex_);
  return T_w_c_.translation();
}

void KeyFrame::setPose(const SE3& T_c_w) {
  std::lock_guard lock(pose_mutex_);
  T_c_w_ = T_c_w;
  T_w_c_ = T_c_w.inverse();
}

SE3 KeyFrame::T_c_parent() const {
  std::lock_guard lock(pose_mutex_);
  return T_c_parent_;
}

std::shared_ptr<MapPoint> KeyFrame::mapPoint(std::size_t feature_index) const {
  std::lock_guard lock(points_mutex_);
  return feature_index < points_.size() ? points_[feature_index] : nullptr;
}

std::vector<std::shared_ptr<MapPoint>> KeyFrame::mapPoints() const {
  std::lock_guard lock(points_mutex_);
  return points_;
}

void KeyFrame::setMapPoint(std::size_t feature_index, std::shared_ptr<MapPoint> point) {
  std::lock_guard lock(points_mutex_);
  if (feature_index < points_.size()) points_[feature_index] = std::move(point);
}

void KeyFrame::eraseMapPoint(std::size_t feature_index) {
  setMapPoint(feature_index, nullptr);
}

void KeyFrame::erasePointById(Id point_id) {
  std::lock_guard lock(points_mutex_);
  for (auto& point : points_) {
    if (point && point->id() == point_id) point.reset();
  }
}

int KeyFrame::trackedMapPoints(int min_observations) const {
  int count = 0;
  for (const auto& point : mapPoints()) {
    if (point && !point->isBad() && point->observationCount() >= min_observations) ++count;
  }
  return count;
}

void KeyFrame::updateConnections() {
  std::map<Id, std::pair<std::shared_ptr<KeyFrame>, int>> shared_counts;
  for (const auto& point : mapPoints()) {
    if (!point || point->isBad()) continue;
    for (const auto& [keyframe, index] : point->observations()) {
      if (keyframe->id() == id_ || keyframe->isBad()) continue;
      auto& entry = shared_counts[keyframe->id()];
      entry.first = keyframe;
      ++entry.second;
    }
  }
  if (shared_counts.empty()) return;

  std::vector<std::pair<std::shared_ptr<KeyFrame>, int>> kept;
  std::pair<std::shared_ptr<KeyFrame>, int> strongest{nullptr, 0};
  for (const auto& [id, entry] : shared_counts) {
    if (entry.second > strongest.second) strongest = entry;
    if (entry.second >= kMinCovisibilityWeight) kept.push_back(entry);
  }
  if (kept.empty()) kept.push_back(strongest);

  const auto self = shared_from_this();
  for (const auto& [keyframe, weight] : kept) keyframe->addConnection(self, weight);

  // The spanning-tree parent is the strongest *older* neighbour, so the tree stays acyclic
  // and the origin (no older keyframe) is its root.
  std::shared_ptr<KeyFrame> new_parent;
  {
    std::lock_guard lock(graph_mutex_);
    connections_.clear();
    for (const auto& [keyframe, weight] : kept) connections_[keyframe->id()] = {keyframe, weight};
    sortConnectionsLocked();
    if (!in_spanning_tree_) {
      for (const auto& [weight, neighbour] : ordered_connections_) {
        auto keyframe = neighbour.lock();
        if (keyframe && keyframe->id() < id_) {
          new_parent = keyframe;
          parent_ = keyframe;
          in_spanning_tree_ = true;
          break;
        }
      }
    }
  }
  if (new_parent) new_parent->addChild(self);
}

void KeyFrame::sortConnectionsLocked() {
  ordered_connections_.clear();
  for (const auto& [id, entry] : connections_)
    ordered_connections_.emplace_back(entry.second, entry.first);
  std::stable_sort(ordered_connections_.begin(), ordered_connections_.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
}

void KeyFrame::addConnection(const std::shared_ptr<KeyFrame>& other, int weight) {
  std::lock_guard lock(graph_mutex_);
  connections_[other->id()] = {other, weight};
  sortConnectionsLocked();
}

void KeyFrame::eraseConnection(Id other) {
  std::lock_guard lock(graph_mutex_);
  if (connections_.erase(other) > 0) sortConnectionsLocked();
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::covisibles(std::size_t max_count) const {
  std::vector<std::shared_ptr<KeyFrame>> result;
  std::lock_guard lock(graph_mutex_);
  for (const auto& [weight, neighbour] : ordered_connections_) {
    if (result.size() >= max_count) break;
    auto keyframe = neighbour.lock();
    if (keyframe && !keyframe->isBad()) result.push_back(std::move(keyframe));
  }
  return result;
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::covisiblesWithMinWeight(int min_weight) const {
  std::vector<std::shared_ptr<KeyFrame>> result;
  std::lock_guard lock(graph_mutex_);
  for (const auto& [weight, neighbour] : ordered_connections_) {
    if (weight < min_weight) break;
    auto keyframe = neighbour.lock();
    if (keyframe && !keyframe->isBad()) result.push_back(std::move(keyframe));
  }
  return result;
}

int KeyFrame::weight(Id other) const {
  std::lock_guard lock(graph_mutex_);
  const auto it = connections_.find(other);
  return it == connections_.end() ? 0 : it->second.second;
}

std::shared_ptr<KeyFrame> KeyFrame::parent() const {
  std::lock_guard lock(graph_mutex_);
  return parent_.lock();
}

void KeyFrame::setParent(const std::shared_ptr<KeyFrame>& parent) {
  std::lock_guard lock(graph_mutex_);
  parent_ = parent;
  in_spanning_tree_ = parent != nullptr;
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::children() const {
  std::vector<std::shared_ptr<KeyFrame>> result;
  std::lock_guard lock(graph_mutex_);
  for (const auto& [id, child] : children_) {
    if (auto keyframe = child.lock()) result.push_back(std::move(keyframe));
  }
  return result;
}

void KeyFrame::addChild(const std::shared_ptr<KeyFrame>& child) {
  std::lock_guard lock(graph_mutex_);
  children_[child->id()] = child;
}

void KeyFrame::eraseChild(Id child) {
  std::lock_guard lock(graph_mutex_);
  children_.erase(child);
}

void KeyFrame::addLoopEdge(const std::shared_ptr<KeyFrame>& other) {
  std::lock_guard lock(graph_mutex_);
  loop_edges_[other->id()] = other;
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::loopEdges() const {
  std::vector<std::shared_ptr<KeyFrame>> result;
  std::lock_guard lock(graph_mutex_);
  for (const auto& [id, other] : loop_edges_) {
    if (auto keyframe = other.lock()) result.push_back(std::move(keyframe));
  }
  return result;
}

void KeyFrame::retire(const std::shared_ptr<KeyFrame>& parent) {
  const SE3 T_w_parent = parent ? parent->T_w_c() : SE3::Identity();
  {
    std::lock_guard lock(pose_mutex_);
    T_c_parent_ = T_c_w_ * T_w_parent;
  }
  {
    std::lock_guard lock(graph_mutex_);
    connections_.clear();
    ordered_connections_.clear();
    children_.clear();
    parent_ = parent;  // kept so that T_c_parent() stays meaningful
  }
  {
    std::lock_guard lock(points_mutex_);
    std::fill(points_.begin(), points_.end(), nullptr);
  }
  bad_.store(true);
}

}  // namespace lumaslam::map
