#include "lumaslam/synth/rolling_shutter.h"

#include "lumaslam/core/error.h"

namespace lumaslam::synth {

RowPoses::RowPoses(std::vector<SE3> per_row) : poses_(std::move(per_row)) {
  if (poses_.empty()) fail("RowPoses: no pose given");
}

double rowTimeOffset(double readout_s, int row, int rows) {
  return readout_s * ((static_cast<double>(row) + 0.5) / static_cast<double>(rows) - 0.5);
}

RowPoses rowPoses(const std::function<SE3(double)>& pose_at, double t, double readout_s, int rows) {
  if (readout_s <= 0.0) return RowPoses(pose_at(t));
  std::vector<SE3> poses;
  poses.reserve(static_cast<size_t>(rows));
  for (int row = 0; row < rows; ++row)
    poses.push_back(pose_at(t + rowTimeOffset(readout_s, row, rows)));
  return RowPoses(std::move(poses));
}

}  // namespace lumaslam::synth
