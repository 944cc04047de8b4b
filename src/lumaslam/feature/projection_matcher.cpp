#include "lumaslam/feature/projection_matcher.h"

#include <algorithm>
#include <limits>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/descriptor_matcher.h"

namespace lumaslam::feature {

Descriptor descriptorAt(const cv::Mat& descriptors, int row) {
  checkDescriptors(descriptors, "descriptorAt");
  if (row < 0 || row >= descriptors.rows) {
    fail("descriptorAt: row {} out of range [0, {})", row, descriptors.rows);
  }
  Descriptor descriptor;
  std::copy_n(descriptors.ptr<std::uint8_t>(row), kDescriptorBytes, descriptor.begin());
  return descriptor;
}

std::vector<cv::DMatch> matchByProjection(const std::vector<ProjectedPoint>& points,
                                          const FeatureGrid& grid, const cv::Mat& descriptors,
                                          const ScaleLevels& levels,
                                          const ProjectionSearchOptions& options) {
  const std::vector<cv::KeyPoint>& keypoints = grid.keypoints();
  checkDescriptors(descriptors, "matchByProjection", static_cast<int>(keypoints.size()));
  constexpr int kNone = std::numeric_limits<int>::max();

  // Winner per feature: the point index and its distance.
  std::vector<int> pointOfFeature(keypoints.size(), -1);
  std::vector<int> distanceOfFeature(keypoints.size(), kNone);
  for (int p = 0; p < static_cast<int>(points.size()); ++p) {
    const ProjectedPoint& point = points[p];
    const int level = std::clamp(point.predictedLevel, 0, levels.count() - 1);
    const float radius = options.radius * levels.scale(level);
    const int minLevel = std::max(0, level - options.levelsBelow);
    const int maxLevel = level + options.levelsAbove;

    int bestDistance = kNone;
    int bestLevel = -1;
    int bestFeature = -1;
    int secondDistance = kNone;
    int secondLevel = -1;
    for (const std::size_t f : grid.featuresInArea(point.uv, radius, minLevel, maxLevel)) {
      const int distance = hammingDistance(point.descriptor.data(),
                                           descriptors.ptr<std::uint8_t>(static_cast<int>(f)));
      if (distance < bestDistance) {
        secondDistance = bestDistance;
        secondLevel = bestLevel;
        bestDistance = distance;
        bestLevel = keypoints[f].octave;
        bestFeature = static_cast<int>(f);
      } else if (distance < secondDistance) {
        secondDistance = distance;
        secondLevel = keypoints[f].octave;
      }
    }
    if (bestFeature < 0 || bestDistance > options.maxDistance) continue;
    // As ORB-SLAM: an ambiguous runner-up only matters at the same scale.
    if (options.ratio < 1.0f && secondDistance != kNone && bestLevel == secondLevel &&
        bestDistance > options.ratio * secondDistance) {
      continue;
    }
    if (bestDistance < distanceOfFeature[bestFeature]) {
      pointOfFeature[bestFeature] = p;
      distanceOfFeature[bestFeature] = bestDistance;
    }
  }

  std::vector<cv::DMatch> matches;
  std::vector<float> rotations;
  for (int f = 0; f < static_cast<int>(keypoints.size()); ++f) {
    if (pointOfFeature[f] < 0) continue;
    matches.emplace_back(pointOfFeature[f], f, static_cast<float>(distanceOfFeature[f]));
    rotations.push_back(points[pointOfFeature[f]].angle - keypoints[f].angle);
  }
  if (options.checkRotation) {
    std::vector<cv::DMatch> consistent;
    for (const std::size_t index : rotationConsistentIndices(rotations, options.rotation)) {
      consistent.push_back(matches[index]);
    }
    matches = std::move(consistent);
  }
  std::sort(matches.begin(), matches.end(),
            [](const cv::DMatch& a, const cv::DMatch& b) { return a.queryIdx < b.queryIdx; });
  return matches;
}

}  // namespace lumaslam::feature
