#pragma once
// Turns a raw YOLOv5 output tensor (1 x N x (5 + C): cx, cy, w, h, objectness, C class
// scores, all in network-input pixels / probabilities) into final detections.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/detect/detection.h"
#include "lumaslam/detect/letterbox.h"

namespace lumaslam::detect {

struct YoloDecodeParams {
  float confidence_threshold = 0.25f;  // on objectness * best class score
  float nms_threshold = 0.45f;
  std::vector<int> class_ids;  // kept classes; empty = all
};

// Confidence = objectness * class score of the best class; rows below the threshold or of
// an unwanted class are dropped; class-wise NMS; boxes mapped to the image and clipped.
// Sorted by score, highest first. Throws Error when the tensor is not 1xNx(5+C) or
// Nx(5+C) with C == names.size().
Detections decodeYoloOutput(const cv::Mat& output, const LetterboxTransform& transform,
                            const std::vector<std::string>& names, const YoloDecodeParams& params);

}  // namespace lumaslam::detect
