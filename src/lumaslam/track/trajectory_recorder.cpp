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

void TrajectoryRecorder::recordTracked(double timestamp, const SE3& T_c_w,
                                       std::shared_ptr<map::KeyFrame> reference) {
  const SE3 T_c_r = T_c_w * reference->T_w_c();
  records_.push_back({timestamp, T_c_r, std::move(reference)});
}

void TrajectoryRecorder::recordLost(double timestamp) {
  records_.push_back({timestamp, SE3::Identity(), nullptr});
}

Trajectory TrajectoryRecorder::frames() const {
  Trajectory trajectory;
  for (const auto& record : records_) {
    if (!record.reference) continue;
    const SE3 T_c_w = record.T_c_r * keyFramePose_T_c_w(*record.reference);
    trajectory.push_back({record.timestamp, T_c_w.inverse()});
  }
  return trajectory;
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
