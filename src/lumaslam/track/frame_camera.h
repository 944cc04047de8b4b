#pragma once
// What tracking needs to know of the camera: a pinhole with optional radial-tangential
// distortion (keypoints are undistorted, images are not), and for stereo/RGB-D the baseline
// times fx and the close-point depth (ORB-SLAM's ThDepth * baseline).
#include <array>

#include <opencv2/core.hpp>

#include "lumaslam/map/feature_set.h"
#include "lumaslam/optimize/camera_intrinsics.h"

namespace lumaslam::track {

struct FrameCamera {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3
  cv::Size size;
  double bf = 0.0;           // 0: monocular
  double close_depth = 0.0;  // metres; points nearer are "close" (reliable depth)

  bool hasDistortion() const;
  cv::Mat K() const;
  map::PinholeIntrinsics intrinsics() const { return {fx, fy, cx, cy, bf}; }
  optimize::CameraIntrinsics optimizerIntrinsics() const { return {fx, fy, cx, cy, bf}; }
  // Bounds of the undistorted image (the area undistorted keypoints can fall in).
  cv::Rect2f undistortedBounds() const;
};

}  // namespace lumaslam::track
