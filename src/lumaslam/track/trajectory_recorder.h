#pragma once
// Every frame's pose stored relative to its reference keyframe (as ORB-SLAM does), so that the
// exported trajectory benefits from later bundle adjustment and loop closing. Retired
// keyframes are followed up their spanning-tree parents.
#include <memory>
#include <vector>

#include "lumaslam/core/pose.h"
#include "lumaslam/map/keyframe.h"

namespace lumaslam::track {

class TrajectoryRecorder {
 public:
  void recordTracked(double timestamp, const SE3& T_c_w, std::shared_ptr<map::KeyFrame> reference);
  void recordLost(double timestamp);

  // Tracked frames only (lost frames get no invented pose), T_w_c in the map frame.
  Trajectory frames() const;
  std::size_t trackedCount() const;
  std::size_t lostCount() const;

 private:
  struct Record {
    double timestamp;
    SE3 T_c_r;
    std::shared_ptr<map::KeyFrame> reference;  // null: lost
  };
  std::vector<Record> records_;
};

// Current world pose of a keyframe, through its parents if it was retired.
SE3 keyFramePose_T_c_w(const map::KeyFrame& keyframe);

// Keyframes of a map as a trajectory (T_w_c), sorted by timestamp.
Trajectory keyFrameTrajectory(const std::vector<std::shared_ptr<map::KeyFrame>>& keyframes);

}  // namespace lumaslam::track
