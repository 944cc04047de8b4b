#include "lumaslam/detect/detection_eval.h"

#include <algorithm>
#include <numeric>

namespace lumaslam::detect {

double MatchCounts::recall() const {
  const int truth = true_positives + false_negatives;
  return truth == 0 ? 1.0 : static_cast<double>(true_positives) / truth;
}

double MatchCounts::precision() const {
  const int detected = true_positives + false_positives;
  return detected == 0 ? 1.0 : static_cast<double>(true_positives) / detected;
}

MatchCounts& MatchCounts::operator+=(const MatchCounts& other) {
  true_positives += other.true_positives;
  false_positives += other.false_positives;
  false_negatives += other.false_negatives;
  return *this;
}

MatchCounts matchDetections(const std::vector<cv::Rect2f>& truth, const Detections& detections,
                            float min_iou) {
  std::vector<std::size_t> order(detections.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return detections[a].score > detections[b].score;
  });
  std::vector<bool> matched(truth.size(), false);
  MatchCounts counts;
  for (const std::size_t d : order) {
    int best = -1;
    float best_iou = min_iou;
    for (std::size_t t = 0; t < truth.size(); ++t) {
      if (matched[t]) continue;
      const float iou = intersectionOverUnion(detections[d].box, truth[t]);
      if (iou >= best_iou) {
        best_iou = iou;
        best = static_cast<int>(t);
      }
    }
    if (best >= 0) {
      matched[static_cast<std::size_t>(best)] = true;
      ++counts.true_positives;
    } else {
      ++counts.false_positives;
    }
  }
  counts.false_negatives = static_cast<int>(std::count(matched.begin(), matched.end(), false));
  return counts;
}

}  // namespace lumaslam::detect
