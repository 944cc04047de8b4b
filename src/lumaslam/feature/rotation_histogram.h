#pragma once
// Rotation-consistency check of ORB-SLAM's matchers: between two views of a rigid scene,
// correct matches share about the same keypoint angle change. Histogram the changes and keep
// only matches in the (up to) three fullest bins.
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::feature {

struct RotationHistogramOptions {
  int bins = 30;  // 12 degrees each
  int keptBins = 3;
  // A runner-up bin is kept only if it holds more than this fraction of the fullest bin.
  float minFractionOfLargest = 0.1f;
};

// Indices (into `rotationsDegrees`) of the consistent entries, in increasing order.
std::vector<std::size_t> rotationConsistentIndices(const std::vector<float>& rotationsDegrees,
                                                   const RotationHistogramOptions& options = {});

// Keeps the matches whose angle change (query angle - train angle) is consistent.
std::vector<cv::DMatch> filterByRotationConsistency(const std::vector<cv::DMatch>& matches,
                                                    const std::vector<cv::KeyPoint>& query,
                                                    const std::vector<cv::KeyPoint>& train,
                                                    const RotationHistogramOptions& options = {});

}  // namespace lumaslam::feature
