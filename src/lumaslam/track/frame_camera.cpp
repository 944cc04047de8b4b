#include "lumaslam/track/frame_camera.h"

#include <algorithm>
#include <vector>

#include <opencv2/calib3d.hpp>

namespace lumaslam::track {

bool FrameCamera::hasDistortion() const {
  return std::any_of(distortion.begin(), distortion.end(), [](double d) { return d != 0.0; });
}

cv::Mat FrameCamera::K() const {
  return (cv::Mat_<double>(3, 3) << fx, 0, cx, 0, fy, cy, 0, 0, 1);
}

cv::Rect2f FrameCamera::undistortedBounds() const {
  const auto w = static_cast<float>(size.width);
  const auto h = static_cast<float>(size.height);
  if (!hasDistortion()) return {0.0F, 0.0F, w, h};
  std::vector<cv::Point2f> corners{{0, 0}, {w, 0}, {0, h}, {w, h}};
  cv::undistortPoints(corners, corners, K(), cv::Mat(distortion), cv::noArray(), K());
  const float x0 = std::min(corners[0].x, corners[2].x);
  const float x1 = std::max(corners[1].x, corners[3].x);
  const float y0 = std::min(corners[0].y, corners[1].y);
  const float y1 = std::max(corners[2].y, corners[3].y);
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace lumaslam::track
