#pragma once
// What tracking needs to know of the camera: the pinhole of the tracked images (keypoints are
// undistorted with it, images are not), and for stereo/RGB-D the baseline times fx and the
// close-point depth (ORB-SLAM's ThDepth * baseline).
#include <opencv2/core.hpp>

#include "lumaslam/camera/pinhole_camera.h"
#include "lumaslam/core/camera_intrinsics.h"

namespace lumaslam::track {

struct FrameCamera {
  camera::PinholeCamera pinhole;
  double bf = 0.0;           // 0: monocular
  double close_depth = 0.0;  // metres; points nearer are "close" (reliable depth)

  cv::Size size() const { return {pinhole.size().width, pinhole.size().height}; }
  CameraIntrinsics intrinsics() const {
    return {pinhole.fx(), pinhole.fy(), pinhole.cx(), pinhole.cy(), bf};
  }
};

}  // namespace lumaslam::track
