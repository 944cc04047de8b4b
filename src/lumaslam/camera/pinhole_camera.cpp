#include "lumaslam/camera/pinhole_camera.h"

#include <opencv2/calib3d.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::camera {

PinholeCamera::PinholeCamera(double fx, double fy, double cx, double cy, ImageSize size,
                             const std::array<double, 5>& distortion)
    : fx_(fx), fy_(fy), cx_(cx), cy_(cy), size_(size), distortion_(distortion) {
  if (!(fx > 0.0) || !(fy > 0.0))
    fail("PinholeCamera: focal lengths must be > 0, got fx={} fy={}", fx, fy);
  if (size.width <= 0 || size.height <= 0) {
    fail("PinholeCamera: image size must be positive, got {}x{}", size.width, size.height);
  }
}

PinholeCamera PinholeCamera::fromSettings(const CameraSettings& settings) {
  const CameraSettings s = settings.atWorkingSize();
  return PinholeCamera(s.fx, s.fy, s.cx, s.cy, s.size, s.distortion);
}

cv::Matx33d PinholeCamera::K() const {
  return {fx_, 0.0, cx_, 0.0, fy_, cy_, 0.0, 0.0, 1.0};
}

cv::Mat PinholeCamera::distortionCoefficients() const {
  return cv::Mat(1, 5, CV_64F, const_cast<double*>(distortion_.data())).clone();
}

bool PinholeCamera::hasDistortion() const {
  for (const double d : distortion_) {
    if (d != 0.0) return true;
  }
  return false;
}

PinholeCamera PinholeCamera::undistorted() const {
  return PinholeCamera(fx_, fy_, cx_, cy_, size_);
}

std::vector<cv::Point2f> PinholeCamera::undistortPoints(const std::vector<cv::Point2f>& raw) const {
  if (!hasDistortion() || raw.empty()) return raw;
  std::vector<cv::Point2f> ideal;
  cv::undistortPoints(raw, ideal, K(), distortionCoefficients(), cv::noArray(), K(),
                      undistortTermination());
  return ideal;
}

std::vector<cv::KeyPoint> PinholeCamera::undistortKeypoints(
    const std::vector<cv::KeyPoint>& raw) const {
  if (!hasDistortion()) return raw;
  std::vector<cv::Point2f> points;
  cv::KeyPoint::convert(raw, points);
  const auto ideal = undistortPoints(points);
  std::vector<cv::KeyPoint> out = raw;
  for (std::size_t i = 0; i < out.size(); ++i) out[i].pt = ideal[i];
  return out;
}

std::vector<cv::Point2f> PinholeCamera::distortPoints(const std::vector<cv::Point2f>& ideal) const {
  if (!hasDistortion() || ideal.empty()) return ideal;
  std::vector<cv::Point3d> rays;
  rays.reserve(ideal.size());
  for (const auto& p : ideal) rays.emplace_back((p.x - cx_) / fx_, (p.y - cy_) / fy_, 1.0);
  std::vector<cv::Point2d> raw;
  cv::projectPoints(rays, cv::Vec3d::zeros(), cv::Vec3d::zeros(), K(), distortionCoefficients(),
                    raw);
  return {raw.begin(), raw.end()};
}

cv::Rect2f PinholeCamera::undistortedBounds() const {
  const auto w = static_cast<float>(size_.width);
  const auto h = static_cast<float>(size_.height);
  if (!hasDistortion()) return {0.0F, 0.0F, w, h};
  const auto corners = undistortPoints({{0, 0}, {w, 0}, {0, h}, {w, h}});
  const float x0 = std::min(corners[0].x, corners[2].x);
  const float x1 = std::max(corners[1].x, corners[3].x);
  const float y0 = std::min(corners[0].y, corners[1].y);
  const float y1 = std::max(corners[2].y, corners[3].y);
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace lumaslam::camera
