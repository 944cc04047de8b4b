#include "lumaslam/detect/detection.h"

namespace lumaslam::detect {

float intersectionOverUnion(const cv::Rect2f& a, const cv::Rect2f& b) {
  const float intersection = (a & b).area();
  const float union_area = a.area() + b.area() - intersection;
  return union_area > 0.0f ? intersection / union_area : 0.0f;
}

std::vector<cv::Rect2f> boxesOf(const Detections& detections) {
  std::vector<cv::Rect2f> boxes;
  boxes.reserve(detections.size());
  for (const auto& detection : detections) boxes.push_back(detection.box);
  return boxes;
}

}  // namespace lumaslam::detect
