#include "lumaslam/detect/box_propagation.h"

#include <algorithm>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/core/gray_image.h"

namespace lumaslam::detect {
namespace {

float median(std::vector<float> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

cv::Rect innerRegion(const cv::Rect2f& box, float fraction, const cv::Size& size) {
  const float w = box.width * fraction;
  const float h = box.height * fraction;
  const cv::Rect2f inner(box.x + (box.width - w) / 2, box.y + (box.height - h) / 2, w, h);
  return cv::Rect(inner) & cv::Rect(cv::Point(), size);
}

cv::Rect2f clipped(const cv::Rect2f& box, const cv::Size& size) {
  return box & cv::Rect2f(0, 0, static_cast<float>(size.width), static_cast<float>(size.height));
}

}  // namespace

Detections propagateDetections(const cv::Mat& previous, const cv::Mat& next,
                               const Detections& detections, const PropagationParams& params) {
  if (previous.size() != next.size() || previous.depth() != CV_8U || next.depth() != CV_8U) {
    fail("propagateDetections: expected two 8-bit images of the same size, found {}x{} and {}x{}",
         previous.cols, previous.rows, next.cols, next.rows);
  }
  if (detections.empty()) return {};
  const cv::Mat previous_gray = toGray(previous);
  const cv::Mat next_gray = toGray(next);

  Detections moved = detections;
  for (auto& detection : moved) {
    const cv::Rect region = innerRegion(detection.box, params.inner_fraction, previous_gray.size());
    if (region.width < 4 || region.height < 4) continue;
    std::vector<cv::Point2f> corners;
    cv::goodFeaturesToTrack(previous_gray(region), corners, params.max_features, 0.01, 3.0);
    if (static_cast<int>(corners.size()) < params.min_tracked) continue;
    for (auto& corner : corners)
      corner += cv::Point2f(static_cast<float>(region.x), static_cast<float>(region.y));

    std::vector<cv::Point2f> tracked;
    std::vector<uchar> status;
    std::vector<float> error;
    cv::calcOpticalFlowPyrLK(previous_gray, next_gray, corners, tracked, status, error);
    std::vector<float> dx;
    std::vector<float> dy;
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if (!status[i]) continue;
      dx.push_back(tracked[i].x - corners[i].x);
      dy.push_back(tracked[i].y - corners[i].y);
    }
    if (static_cast<int>(dx.size()) < params.min_tracked) continue;
    detection.box.x += median(dx);
    detection.box.y += median(dy);
    detection.box = clipped(detection.box, next_gray.size());
  }
  // A box pushed entirely out of the image is gone.
  std::erase_if(moved, [](const Detection& d) { return d.box.area() <= 0.0f; });
  return moved;
}

}  // namespace lumaslam::detect
