#pragma once
// Rectifies an unrectified stereo pair (EuRoC) from its calibration: cv::stereoRectify for the
// rectifying rotations and the common pinhole camera, cv::initUndistortRectifyMap once, then
// cv::remap per frame. After rectify(), a point's rows agree in both images and the right
// column is u_r = u_l - bf / z.
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lumaslam/camera/camera_settings.h"
#include "lumaslam/camera/pinhole_camera.h"
#include "lumaslam/core/pose.h"

namespace lumaslam::camera {

class StereoRectifier {
 public:
  // T_c1_c2: pose of the right camera in the left camera frame (Stereo.T_c1_c2).
  // alpha: cv::stereoRectify's free scaling, 0 keeps only valid pixels (no black borders).
  StereoRectifier(const PinholeCamera& left, const PinholeCamera& right, const SE3& T_c1_c2,
                  double alpha = 0.0);
  // Camera 1 and the pair of a stereo settings file; needs Camera2.* (an unrectified pair),
  // throws Error naming `origin` (the settings file) otherwise.
  static StereoRectifier fromSettings(const CameraSettings& left, const StereoSettings& stereo,
                                      std::string_view origin, double alpha = 0.0);

  // Both images remapped (bilinear); each must have the calibrated size.
  std::pair<cv::Mat, cv::Mat> rectify(const cv::Mat& left, const cv::Mat& right) const;
  cv::Mat rectifyLeft(const cv::Mat& image) const;
  cv::Mat rectifyRight(const cv::Mat& image) const;
  // Raw pixels of the original images -> pixels of the rectified images.
  std::vector<cv::Point2f> rectifyLeftPoints(const std::vector<cv::Point2f>& raw) const;
  std::vector<cv::Point2f> rectifyRightPoints(const std::vector<cv::Point2f>& raw) const;

  // Distortion-free camera of both rectified images.
  const PinholeCamera& rectifiedCamera() const { return rectified_; }
  double baseline() const { return baseline_; }  // metres
  double bf() const { return baseline_ * rectified_.fx(); }
  // Rotation from the original left camera frame into the rectified left frame
  // (p_rect = R_rect_c1 * p_c1): poses tracked in rectified frames map back with it.
  const Eigen::Matrix3d& R_rect_c1() const { return R_rect_c1_; }

 private:
  cv::Mat remap(const cv::Mat& image, const cv::Mat& mapX, const cv::Mat& mapY,
                const char* side) const;

  PinholeCamera left_, right_, rectified_;
  cv::Mat R1_, R2_, P1_, P2_;
  cv::Mat leftMapX_, leftMapY_, rightMapX_, rightMapY_;
  double baseline_ = 0.0;
  Eigen::Matrix3d R_rect_c1_;
};

}  // namespace lumaslam::camera
