#pragma once
// Pinhole camera with OpenCV radial-tangential distortion (k1, k2, p1, p2, k3).
// project/unproject work on ideal (undistorted) pixels: keypoints are undistorted once with
// undistortPoints, as in ORB-SLAM, and everything after that is plain pinhole geometry.
#include <array>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lumaslam/camera/camera_settings.h"

namespace lumaslam::camera {

class PinholeCamera {
 public:
  PinholeCamera(double fx, double fy, double cx, double cy, ImageSize size,
                const std::array<double, 5>& distortion = {});
  // Intrinsics at the working size (after Camera.newWidth/newHeight, if set).
  static PinholeCamera fromSettings(const CameraSettings& settings);

  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  ImageSize size() const { return size_; }
  cv::Matx33d K() const;
  cv::Mat distortionCoefficients() const;  // 1x5 CV_64F, OpenCV order
  const std::array<double, 5>& distortion() const { return distortion_; }
  bool hasDistortion() const;
  // The same intrinsics without distortion: the camera of undistorted pixels.
  PinholeCamera undistorted() const;

  // Ideal pixel of a point in the camera frame (z > 0 is the caller's job).
  Eigen::Vector2d project(const Eigen::Vector3d& p_c) const {
    return {fx_ * p_c.x() / p_c.z() + cx_, fy_ * p_c.y() / p_c.z() + cy_};
  }
  // Point in the camera frame at depth z (not range) behind an ideal pixel.
  Eigen::Vector3d unproject(const Eigen::Vector2d& uv, double z) const {
    return {(uv.x() - cx_) / fx_ * z, (uv.y() - cy_) / fy_ * z, z};
  }
  bool inImage(const Eigen::Vector2d& uv) const {
    return uv.x() >= 0.0 && uv.y() >= 0.0 && uv.x() < size_.width && uv.y() < size_.height;
  }

  // Raw (distorted) pixels -> ideal pixels, via cv::undistortPoints iterated to convergence
  // (undistortTermination) so that it stays sub-0.01 px at the corners of strong lenses.
  std::vector<cv::Point2f> undistortPoints(const std::vector<cv::Point2f>& raw) const;
  // Same for keypoints; only pt changes (size, angle, octave, response are kept).
  std::vector<cv::KeyPoint> undistortKeypoints(const std::vector<cv::KeyPoint>& raw) const;
  // Ideal pixels -> raw pixels (cv::projectPoints): where a pinhole pixel lands in the image.
  std::vector<cv::Point2f> distortPoints(const std::vector<cv::Point2f>& ideal) const;
  // Bounding box of the undistorted image corners: where undistorted keypoints can lie.
  cv::Rect2f undistortedBounds() const;

  // OpenCV's default 5 fixed-point iterations leave errors up to 0.57 px at the corners of
  // the EuRoC lens (k1 = -0.28); iterating to 1e-3 px costs about 2.5x (~0.8 ms per 1000 points).
  static cv::TermCriteria undistortTermination() {
    return {cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-3};
  }

 private:
  double fx_, fy_, cx_, cy_;
  ImageSize size_;
  std::array<double, 5> distortion_;
};

}  // namespace lumaslam::camera
