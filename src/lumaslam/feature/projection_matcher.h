#pragma once
// Guided matching (ORB-SLAM's SearchByProjection): points with a predicted pixel position,
// pyramid level and descriptor (e.g. map points projected with the predicted pose) are matched
// to the frame's features near that position. Plain data, so the tracker can feed it anything.
#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/feature/feature_grid.h"
#include "lumaslam/feature/hamming.h"
#include "lumaslam/feature/rotation_histogram.h"
#include "lumaslam/feature/scale_levels.h"

namespace lumaslam::feature {

using Descriptor = std::array<std::uint8_t, kDescriptorBytes>;

struct ProjectedPoint {
  cv::Point2f uv;          // predicted position, level-0 pixels
  int predictedLevel = 0;  // predicted pyramid level (from the point's distance)
  Descriptor descriptor{};
  // Angle (degrees) of the point's keypoint in the view it came from; needed only when
  // ProjectionSearchOptions::checkRotation is set (frame-to-frame tracking).
  float angle = 0.0f;
};

struct ProjectionSearchOptions {
  // Window half-size in level-0 pixels at level 0; scaled by scale(predictedLevel).
  float radius = 3.0f;
  int maxDistance = kThHigh;
  // Ratio test between the best and second-best candidate at the same level (1 disables).
  float ratio = 0.8f;
  // Candidate octaves: [predictedLevel - levelsBelow, predictedLevel + levelsAbove].
  int levelsBelow = 1;
  int levelsAbove = 1;
  bool checkRotation = false;
  RotationHistogramOptions rotation{};
};

// Each feature is matched at most once (the point with the smaller distance wins).
// Returns DMatch(queryIdx = point index, trainIdx = feature index, distance).
// `descriptors`: CV_8UC1 N x 32 rows for grid.keypoints(); throws Error otherwise.
std::vector<cv::DMatch> matchByProjection(const std::vector<ProjectedPoint>& points,
                                          const FeatureGrid& grid, const cv::Mat& descriptors,
                                          const ScaleLevels& levels,
                                          const ProjectionSearchOptions& options = {});

// Copies row `row` of a CV_8UC1 N x 32 descriptor matrix.
Descriptor descriptorAt(const cv::Mat& descriptors, int row);

}  // namespace lumaslam::feature
