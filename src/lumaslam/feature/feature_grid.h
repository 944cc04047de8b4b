#pragma once
// Keypoints bucketed into a coarse grid so "which features lie near (u, v)" costs a few cells
// instead of a scan (ORB-SLAM's Frame::GetFeaturesInArea). The tracker builds one per frame.
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::feature {

class FeatureGrid {
 public:
  static constexpr int kDefaultColumns = 64;
  static constexpr int kDefaultRows = 48;

  // `bounds`: the area the grid covers (the image, or the undistorted image's bounding box).
  // Keypoints outside it are kept in keypoints() but never returned by queries.
  FeatureGrid(std::vector<cv::KeyPoint> keypoints, const cv::Rect2f& bounds,
              int columns = kDefaultColumns, int rows = kDefaultRows);
  FeatureGrid(std::vector<cv::KeyPoint> keypoints, cv::Size imageSize);

  // Indices of keypoints with |x - cx| < radius and |y - cy| < radius (a square window, as
  // ORB-SLAM) and, when minLevel/maxLevel are >= 0, octave in [minLevel, maxLevel].
  std::vector<std::size_t> featuresInArea(cv::Point2f center, float radius, int minLevel = -1,
                                          int maxLevel = -1) const;

  const std::vector<cv::KeyPoint>& keypoints() const { return keypoints_; }
  const cv::Rect2f& bounds() const { return bounds_; }
  int columns() const { return columns_; }
  int rows() const { return rows_; }

 private:
  const std::vector<std::size_t>& cell(int column, int row) const {
    return cells_[static_cast<std::size_t>(row) * columns_ + column];
  }

  std::vector<cv::KeyPoint> keypoints_;
  cv::Rect2f bounds_;
  int columns_;
  int rows_;
  float cellsPerPixelX_;
  float cellsPerPixelY_;
  std::vector<std::vector<std::size_t>> cells_;
};

}  // namespace lumaslam::feature
