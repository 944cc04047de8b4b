#pragma once
// A camera pose as the public API returns it: T_w_c maps camera points into the world (the
// camera at the first keyframe), timestamps in seconds.
#include <vector>

#include <Eigen/Core>

namespace lumaslam {

struct CameraPose {
  double timestamp = 0.0;
  Eigen::Matrix4d T_w_c = Eigen::Matrix4d::Identity();
};

using CameraTrajectory = std::vector<CameraPose>;

}  // namespace lumaslam
