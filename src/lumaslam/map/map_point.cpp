#include "lumaslam/map/map_point.h"

#include <algorithm>
#include <cmath>

#include "lumaslam/map/keyframe.h"

namespace lumaslam::map {

MapPoint::MapPoint(Id id, const Eigen::Vector3d& position_w,
                   const std::shared_ptr<KeyFrame>& reference)
    : id_(id),
      reference_id_(reference ? reference->id() : 0),
      reference_(reference),
      position_w_(position_w) {}

MapPoint::MapPoint(Id id, const Eigen::Vector3d& position_w, Id reference_id,
                   const std::shared_ptr<KeyFrame>& reference)
    : id_(id), reference_id_(reference_id), reference_(reference), position_w_(position_w) {}

std::shared_ptr<KeyFrame> MapPoint::referenceKeyFrame() const {
  return reference_.lock();
}

Eigen::Vector3d MapPoint::position() const {
  std::lock_guard lock(mutex_);
  return position_w_;
}

void MapPoint::setPosition(const Eigen::Vector3d& position_w) {
  std::lock_guard lock(mutex_);
  position_w_ = position_w;
}

Eigen::Vector3d MapPoint::normal() const {
  std::lock_guard lock(mutex_);
  return normal_;
}

double MapPoint::minDistance() const {
  std::lock_guard lock(mutex_);
  return 0.8 * min_distance_;
}

double MapPoint::maxDistance() const {
  std::lock_guard lock(mutex_);
  return 1.2 * max_distance_;
}

Descriptor MapPoint::descriptor() const {
  std::lock_guard lock(mutex_);
  return descriptor_;
}

void MapPoint::addObservation(const std::shared_ptr<KeyFrame>& keyframe, int feature_index) {
  const bool stereo = keyframe->features().hasStereo(static_cast<std::size_t>(feature_index));
  std::lock_guard lock(mutex_);
  const auto [it, inserted] =
      observations_.try_emplace(keyframe->id(), Observation{keyframe, feature_index, stereo});
  if (!inserted) return;
  observation_count_ += stereo ? 2 : 1;
}

bool MapPoint::eraseObservation(Id keyframe_id) {
  std::lock_guard lock(mutex_);
  const auto it = observations_.find(keyframe_id);
  if (it == observations_.end()) return false;
  observation_count_ -= it->second.stereo ? 2 : 1;
  observations_.erase(it);
  return observation_count_ <= 2;
}

std::vector<std::pair<std::shared_ptr<KeyFrame>, int>> MapPoint::observations() const {
  std::vector<std::pair<std::shared_ptr<KeyFrame>, int>> result;
  std::lock_guard lock(mutex_);
  result.reserve(observations_.size());
  for (const auto& [id, observation] : observations_) {
    if (auto keyframe = observation.keyframe.lock())
      result.emplace_back(keyframe, observation.index);
  }
  return result;
}

int MapPoint::observationCount() const {
  std::lock_guard lock(mutex_);
  return observation_count_;
}

int MapPoint::featureIndexIn(Id keyframe_id) const {
  std::lock_guard lock(mutex_);
  const auto it = observations_.find(keyframe_id);
  return it == observations_.end() ? -1 : it->second.index;
}

void MapPoint::updateNormalAndDepth() {
  const auto observing = observations();
  const auto reference = referenceKeyFrame();
  if (observing.empty() || !reference) return;
  const Eigen::Vector3d position_w = position();

  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
  for (const auto& [keyframe, index] : observing) {
    normal_sum += (position_w - keyframe->center()).normalized();
  }
  const double distance = (position_w - reference->center()).norm();
  const int index = featureIndexIn(reference->id());
  const auto& pyramid = reference->pyramid();
  const int level =
      index >= 0
          ? std::clamp(reference->features().keypoints[static_cast<std::size_t>(index)].octave, 0,
                       pyramid.count() - 1)
          : 0;
  const double max_distance = distance * pyramid.scale(level);

  std::lock_guard lock(mutex_);
  normal_ = normal_sum.normalized();
  max_distance_ = max_distance;
  min_distance_ = max_distance / pyramid.scale(pyramid.count() - 1);
}

void MapPoint::computeDistinctiveDescriptor() {
  std::vector<Descriptor> candidates;
  for (const auto& [keyframe, index] : observations()) {
    candidates.push_back(keyframe->descriptor(static_cast<std::size_t>(index)));
  }
  if (candidates.empty()) return;
  const std::size_t n = candidates.size();
  std::size_t best = 0;
  int best_median = INT32_MAX;
  std::vector<int> distances(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j)
      distances[j] = hammingDistance(candidates[i], candidates[j]);
    std::nth_element(distances.begin(), distances.begin() + (n - 1) / 2, distances.end());
    const int median = distances[(n - 1) / 2];
    if (median < best_median) {
      best_median = median;
      best = i;
    }
  }
  std::lock_guard lock(mutex_);
  descriptor_ = candidates[best];
}

int MapPoint::predictScale(double distance, const feature::ScaleLevels& pyramid) const {
  double max_distance = 0.0;
  {
    std::lock_guard lock(mutex_);
    max_distance = max_distance_;
  }
  if (distance <= 0.0 || max_distance <= 0.0) return 0;
  const int level =
      static_cast<int>(std::ceil(std::log(max_distance / distance) / pyramid.logScaleFactor()));
  return std::clamp(level, 0, pyramid.count() - 1);
}

MapPoint::DerivedState MapPoint::derivedState() const {
  std::lock_guard lock(mutex_);
  return {normal_, min_distance_, max_distance_, descriptor_, visible_.load(), found_.load()};
}

void MapPoint::restoreDerivedState(const DerivedState& state) {
  std::lock_guard lock(mutex_);
  normal_ = state.normal;
  min_distance_ = state.min_distance;
  max_distance_ = state.max_distance;
  descriptor_ = state.descriptor;
  visible_ = state.visible;
  found_ = state.found;
}

double MapPoint::foundRatio() const {
  return static_cast<double>(found_.load()) / static_cast<double>(std::max(1, visible_.load()));
}

std::shared_ptr<MapPoint> MapPoint::replacement() const {
  std::lock_guard lock(mutex_);
  return replaced_by_.lock();
}

void MapPoint::setReplacement(const std::shared_ptr<MapPoint>& by) {
  std::lock_guard lock(mutex_);
  replaced_by_ = by;
}

}  // namespace lumaslam::map
