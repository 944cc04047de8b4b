#pragma once
// One detected object: what it is, how sure the detector is, where it is (image pixels,
// x right, y down, clipped to the image).
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::detect {

struct Detection {
  int class_id = -1;       // index into the detector's class names (-1: unknown)
  std::string class_name;  // e.g. "person"
  float score = 0.0f;      // 0..1
  cv::Rect2f box;
};

using Detections = std::vector<Detection>;

// Intersection over union of two boxes; 0 when either is empty.
float intersectionOverUnion(const cv::Rect2f& a, const cv::Rect2f& b);

// Boxes of `detections` only (for masks and drawing).
std::vector<cv::Rect2f> boxesOf(const Detections& detections);

}  // namespace lumaslam::detect
