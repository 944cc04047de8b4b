#pragma once
// ORB features as ORB-SLAM extracts them: scale pyramid, FAST per grid cell with threshold
// fallback, quadtree distribution to the per-level budget, intensity-centroid orientation,
// steered BRIEF. An optional mask (CV_8U, nonzero = drop) keeps features off e.g. people.
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/feature/orb_settings.h"
#include "lumaslam/feature/scale_levels.h"

namespace lumaslam::feature {

struct OrbFeatures {
  // Level-0 pixel coordinates; octave = pyramid level, size = 31 * scale(octave),
  // angle in degrees [0, 360), response = FAST score at that level.
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;           // CV_8UC1, keypoints.size() x 32
  std::vector<cv::Mat> pyramid;  // level images (sub-images of padded buffers; a copy)
};

class OrbExtractor {
 public:
  // Throws Error if the settings are out of range.
  explicit OrbExtractor(const OrbSettings& settings);

  // `image` CV_8UC1; `mask` empty or CV_8UC1 of the image size. Throws Error naming the
  // problem for anything else. Safe to call from several threads at once.
  OrbFeatures extract(const cv::Mat& image, const cv::Mat& mask = cv::Mat()) const;

  const OrbSettings& settings() const { return settings_; }
  const ScaleLevels& levels() const { return levels_; }
  const std::vector<int>& featureBudget() const { return budget_; }

 private:
  std::vector<cv::Mat> buildPyramid(const cv::Mat& image) const;
  // Keypoints (level coordinates) and descriptors of one pyramid level.
  void extractLevel(const cv::Mat& levelImage, int level, const cv::Mat& mask,
                    std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) const;

  OrbSettings settings_;
  ScaleLevels levels_;
  std::vector<int> budget_;
};

}  // namespace lumaslam::feature
