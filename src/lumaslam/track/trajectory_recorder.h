#pragma once
// Every frame's pose stored relative to its reference keyframe (as ORB-SLAM does), so that the
// exported trajectory benefits from later bundle adjustment and loop closing. Retired
// keyframes are followed up their spanning-tree parents.
#include <map>
#include <memory>
#include <vector>

#include "lumaslam/core/pose.h"
#include "lumaslam/map/keyframe.h"

namespace lumaslam::track {

class TrajectoryRecorder {
 public:
  void recordTracked(double timestamp, const SE3& T_c_w, std::shared_ptr<map::KeyFrame> reference);
  void recordLost(double timestamp);

  // Tracked frames only (lost frames get no invented pose), T_w_c, per map of the atlas: the
  // map each frame's reference keyframe is in now, so that frames of merged maps are together,
  // in the joined map's world. Frames of a reset map (map::kDiscardedMap) are left out.
  std::map<map::MapId, Trajectory> framesByMap() const;
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
// Its map, through its parents if it was retired.
map::MapId keyFrameMapId(const map::KeyFrame& keyframe);

// Keyframes of a map as a trajectory (T_w_c), sorted by timestamp.
Trajectory keyFrameTrajectory(const std::vector<std::shared_ptr<map::KeyFrame>>& keyframes);

}  // namespace lumaslam::track
