#include "lumaslam/track/trajectory_recorder.h"

#include <algorithm>

namespace lumaslam::track {

SE3 keyFramePose_T_c_w(const map::KeyFrame& keyframe) {
  if (!keyframe.isBad()) return keyframe.T_c_w();
  // T_c_w = T_c_parent * T_parent_w, up the chain until a live keyframe.
  SE3 T_c_x = keyframe.T_c_parent();
  auto parent = keyframe.parent();
  while (parent && parent->isBad()) {
    T_c_x = T_c_x * parent->T_c_parent();
    parent = parent->parent();
  }
  return parent ? T_c_x * parent->T_c_w() : T_c_x;
}

map::MapId keyFrameMapId(const map::KeyFrame& keyframe) {
  auto parent = keyframe.isBad() ? keyframe.parent() : nullptr;
  while (parent && parent->isBad()) parent = parent->parent();
  return parent ? parent->mapId() : keyframe.mapId();
}

void TrajectoryRecorder::recordTracked(double timestamp, const SE3& T_c_w,
                                       std::shared_ptr<map::KeyFrame> reference) {
  const SE3 T_c_r = T_c_w * reference->T_w_c();
  records_.push_back({timestamp, T_c_r, std::move(reference)});
}

void TrajectoryRecorder::recordLost(double timestamp) {
  records_.push_back({timestamp, SE3::Identity(), nullptr});
}

std::map<map::MapId, Trajectory> TrajectoryRecorder::framesByMap() const {
  std::map<map::MapId, Trajectory> by_map;
  for (const auto& record : records_) {
    if (!record.reference) continue;
    const map::MapId map = keyFrameMapId(*record.reference);
    if (map == map::kDiscardedMap) continue;  // a reset map: its frames count as lost
    const SE3 T_c_w = record.T_c_r * keyFramePose_T_c_w(*record.reference);
    by_map[map].push_back({record.timestamp, T_c_w.inverse()});
  }
  return by_map;
}

std::size_t TrajectoryRecorder::trackedCount() const {
  return static_cast<std::size_t>(
      std::count_if(records_.begin(), records_.end(), [](const auto& r) { return r.reference; }));
}

std::size_t TrajectoryRecorder::lostCount() const {
  return records_.size() - trackedCount();
}

Trajectory keyFrameTrajectory(const std::vector<std::shared_ptr<map::KeyFrame>>& keyframes) {
  Trajectory trajectory;
  for (const auto& kf : keyframes) {
    trajectory.push_back({kf->timestamp(), keyFramePose_T_c_w(*kf).inverse()});
  }
  std::sort(trajectory.begin(), trajectory.end(),
            [](const auto& a, const auto& b) { return a.timestamp < b.timestamp; });
  return trajectory;
}

}  // namespace lumaslam::track
