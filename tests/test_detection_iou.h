#pragma once
// How well one set of boxes covers another: shared by the detection and propagation tests.
#include <algorithm>

#include "lumaslam/detect/detection.h"

namespace lumaslam::test {

// Mean over directly detected boxes of the best IoU with `boxes`.
inline double meanBestIou(const detect::Detections& direct, const detect::Detections& boxes) {
  if (direct.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& d : direct) {
    float best = 0.0f;
    for (const auto& b : boxes) best = std::max(best, detect::intersectionOverUnion(d.box, b.box));
    sum += best;
  }
  return sum / static_cast<double>(direct.size());
}

}  // namespace lumaslam::test
