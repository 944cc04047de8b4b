#include "lumaslam/feature/feature_grid.h"

#include <algorithm>
#include <cmath>

#include "lumaslam/core/error.h"

namespace lumaslam::feature {

FeatureGrid::FeatureGrid(std::vector<cv::KeyPoint> keypoints, const cv::Rect2f& bounds, int columns,
                         int rows)
    : keypoints_(std::move(keypoints)), bounds_(bounds), columns_(columns), rows_(rows) {
  if (columns < 1 || rows < 1)
    fail("FeatureGrid: needs at least 1x1 cells, got {}x{}", columns, rows);
  if (!(bounds.width > 0) || !(bounds.height > 0)) {
    fail("FeatureGrid: bounds must have a positive size, got {}x{}", bounds.width, bounds.height);
  }
  cellsPerPixelX_ = columns_ / bounds_.width;
  cellsPerPixelY_ = rows_ / bounds_.height;
  cells_.resize(static_cast<std::size_t>(columns_) * rows_);
  for (std::size_t i = 0; i < keypoints_.size(); ++i) {
    const cv::Point2f& p = keypoints_[i].pt;
    const int column = static_cast<int>(std::floor((p.x - bounds_.x) * cellsPerPixelX_));
    const int row = static_cast<int>(std::floor((p.y - bounds_.y) * cellsPerPixelY_));
    if (column < 0 || column >= columns_ || row < 0 || row >= rows_) continue;
    cells_[static_cast<std::size_t>(row) * columns_ + column].push_back(i);
  }
}

FeatureGrid::FeatureGrid(std::vector<cv::KeyPoint> keypoints, cv::Size imageSize)
    : FeatureGrid(std::move(keypoints), cv::Rect2f(0.0f, 0.0f, static_cast<float>(imageSize.width),
                                                   static_cast<float>(imageSize.height))) {}

std::vector<std::size_t> FeatureGrid::featuresInArea(cv::Point2f center, float radius, int minLevel,
                                                     int maxLevel) const {
  std::vector<std::size_t> found;
  const int firstColumn =
      std::max(0, static_cast<int>(std::floor((center.x - bounds_.x - radius) * cellsPerPixelX_)));
  const int lastColumn =
      std::min(columns_ - 1,
               static_cast<int>(std::floor((center.x - bounds_.x + radius) * cellsPerPixelX_)));
  const int firstRow =
      std::max(0, static_cast<int>(std::floor((center.y - bounds_.y - radius) * cellsPerPixelY_)));
  const int lastRow = std::min(
      rows_ - 1, static_cast<int>(std::floor((center.y - bounds_.y + radius) * cellsPerPixelY_)));
  for (int row = firstRow; row <= lastRow; ++row) {
    for (int column = firstColumn; column <= lastColumn; ++column) {
      for (const std::size_t index : cell(column, row)) {
        const cv::KeyPoint& keypoint = keypoints_[index];
        if (minLevel >= 0 && keypoint.octave < minLevel) continue;
        if (maxLevel >= 0 && keypoint.octave > maxLevel) continue;
        if (std::abs(keypoint.pt.x - center.x) < radius &&
            std::abs(keypoint.pt.y - center.y) < radius) {
          found.push_back(index);
        }
      }
    }
  }
  return found;
}

}  // namespace lumaslam::feature
