#pragma once
// Pose conventions (docs/architecture.md): T_a_b maps points from frame b into frame a,
// so T_w_c is the camera-to-world pose. Timestamps are seconds (double).
#include <vector>

#include <Eigen/Geometry>

namespace lumaslam {

using SE3 = Eigen::Isometry3d;

struct StampedPose {
  double timestamp = 0.0;
  SE3 T_w_c = SE3::Identity();
};

using Trajectory = std::vector<StampedPose>;

}  // namespace lumaslam
