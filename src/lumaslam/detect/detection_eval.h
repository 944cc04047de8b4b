#pragma once
// Recall / precision of detections against labelled boxes (one class at a time).
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/detect/detection.h"

namespace lumaslam::detect {

struct MatchCounts {
  int true_positives = 0;
  int false_positives = 0;
  int false_negatives = 0;

  double recall() const;     // TP / (TP + FN); 1 when there is nothing to find
  double precision() const;  // TP / (TP + FP); 1 when nothing was detected
  MatchCounts& operator+=(const MatchCounts& other);
};

// Greedy matching, highest score first: a detection is a hit when its IoU with a not yet
// matched truth box is >= min_iou (the best such box is taken), as in VOC evaluation.
MatchCounts matchDetections(const std::vector<cv::Rect2f>& truth, const Detections& detections,
                            float min_iou = 0.5f);

}  // namespace lumaslam::detect
