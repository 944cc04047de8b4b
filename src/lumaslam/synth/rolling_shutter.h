#pragma once
// Rolling shutter: the rows of an image are exposed one after the other while the sensor is
// read out top to bottom, so under camera motion each row sees the scene from its own pose
// (Kinect v1 colour camera and webcams read out in ~30 ms; Meingast et al., "Geometric models
// of rolling-shutter cameras", 2005). The frame's timestamp is the exposure centre of the
// middle of the image, so its ground-truth pose is the pose of the middle rows.
#include <functional>
#include <vector>

#include "lumaslam/core/pose.h"

namespace lumaslam::synth {

// Camera pose of every image row: a single pose for a global shutter, one per row otherwise.
class RowPoses {
 public:
  explicit RowPoses(const SE3& global) : poses_{global} {}
  explicit RowPoses(std::vector<SE3> per_row);

  const SE3& operator[](int row) const {
    return poses_.size() == 1 ? poses_.front() : poses_[static_cast<size_t>(row)];
  }
  bool global() const { return poses_.size() == 1; }

 private:
  std::vector<SE3> poses_;
};

// Time of row `row`'s exposure centre relative to the frame timestamp, for a readout of
// `readout_s` over `rows` rows: rows start readout_s / rows apart, the middle at 0.
double rowTimeOffset(double readout_s, int row, int rows);

// Poses of the rows of a frame stamped `t`; readout_s <= 0 gives a global shutter.
RowPoses rowPoses(const std::function<SE3(double)>& pose_at, double t, double readout_s, int rows);

}  // namespace lumaslam::synth
