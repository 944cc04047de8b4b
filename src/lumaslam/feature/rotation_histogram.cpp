#include "lumaslam/feature/rotation_histogram.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "lumaslam/core/error.h"

namespace lumaslam::feature {

std::vector<std::size_t> rotationConsistentIndices(const std::vector<float>& rotationsDegrees,
                                                   const RotationHistogramOptions& options) {
  if (options.bins < 1 || options.keptBins < 1) {
    fail("rotationConsistentIndices: bins ({}) and keptBins ({}) must be >= 1", options.bins,
         options.keptBins);
  }
  const float binsPerDegree = options.bins / 360.0f;
  std::vector<int> binOf(rotationsDegrees.size());
  std::vector<int> counts(options.bins, 0);
  for (std::size_t i = 0; i < rotationsDegrees.size(); ++i) {
    float rotation = std::fmod(rotationsDegrees[i], 360.0f);
    if (rotation < 0) rotation += 360.0f;
    binOf[i] = std::min(static_cast<int>(rotation * binsPerDegree), options.bins - 1);
    ++counts[binOf[i]];
  }
  std::vector<int> order(options.bins);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return counts[a] > counts[b]; });

  std::vector<bool> keep(options.bins, false);
  const int largest = counts[order[0]];
  for (int rank = 0; rank < std::min(options.keptBins, options.bins); ++rank) {
    const int count = counts[order[rank]];
    if (count == 0) break;
    if (rank > 0 && count <= options.minFractionOfLargest * largest) break;
    keep[order[rank]] = true;
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < binOf.size(); ++i) {
    if (keep[binOf[i]]) kept.push_back(i);
  }
  return kept;
}

std::vector<cv::DMatch> filterByRotationConsistency(const std::vector<cv::DMatch>& matches,
                                                    const std::vector<cv::KeyPoint>& query,
                                                    const std::vector<cv::KeyPoint>& train,
                                                    const RotationHistogramOptions& options) {
  std::vector<float> rotations;
  rotations.reserve(matches.size());
  for (const cv::DMatch& match : matches) {
    rotations.push_back(query.at(match.queryIdx).angle - train.at(match.trainIdx).angle);
  }
  std::vector<cv::DMatch> kept;
  for (const std::size_t index : rotationConsistentIndices(rotations, options)) {
    kept.push_back(matches[index]);
  }
  return kept;
}

}  // namespace lumaslam::feature
