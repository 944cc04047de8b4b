#pragma once
// Depth as seen by a rectified stereo pair or an RGB-D camera treated as one (ORB-SLAM's
// "virtual right camera"): disparity d = u_l - u_r = bf / z, and points closer than
// ThDepth baselines are "close" (their depth is trusted for a single-frame triangulation).
#include <opencv2/core.hpp>

#include "lumaslam/camera/camera_settings.h"

namespace lumaslam::camera {

class StereoRectifier;

class StereoGeometry {
 public:
  // bf: baseline (m) times the rectified fx (px); thDepth: close/far threshold in baselines.
  StereoGeometry(double bf, double baseline, double thDepth);
  // RGB-D or rectified stereo (Camera.type Rectified): camera 1 and its baseline; an
  // unrectified pair (Camera2.*) throws Error (its bf is only known after rectification: use
  // fromRectifier).
  static StereoGeometry fromSettings(const CameraSettings& camera, const StereoSettings& stereo,
                                     double thDepth);
  static StereoGeometry fromRectifier(const StereoRectifier& rectifier, double thDepth);

  double bf() const { return bf_; }
  double baseline() const { return baseline_; }
  double closeDepth() const { return closeDepth_; }  // metres: ThDepth * baseline

  // Column of the point in the (virtual) right image; z > 0 is the caller's job.
  float rightU(float u, float z) const { return u - static_cast<float>(bf_ / z); }
  double depthFromDisparity(double disparity) const { return bf_ / disparity; }
  bool isClose(double z) const { return z > 0.0 && z < closeDepth_; }

 private:
  double bf_, baseline_, closeDepth_;
};

// Raw depth image (CV_16U, or CV_32F) -> metres as CV_32F: value / depthMapFactor
// (5000 for TUM PNGs). 0 stays 0 and means "no measurement".
cv::Mat depthToMetres(const cv::Mat& raw, double depthMapFactor);

}  // namespace lumaslam::camera
