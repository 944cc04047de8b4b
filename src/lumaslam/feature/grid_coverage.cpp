#include "lumaslam/feature/grid_coverage.h"

#include <algorithm>

#include "lumaslam/core/error.h"

namespace lumaslam::feature {

double gridCoverage(const std::vector<cv::KeyPoint>& keypoints, cv::Size imageSize, int columns,
                    int rows) {
  if (imageSize.width <= 0 || imageSize.height <= 0 || columns < 1 || rows < 1) {
    fail("gridCoverage: bad image size {}x{} or grid {}x{}", imageSize.width, imageSize.height,
         columns, rows);
  }
  std::vector<bool> occupied(static_cast<std::size_t>(columns) * rows, false);
  for (const cv::KeyPoint& keypoint : keypoints) {
    const int column = static_cast<int>(keypoint.pt.x * columns / imageSize.width);
    const int row = static_cast<int>(keypoint.pt.y * rows / imageSize.height);
    if (column < 0 || column >= columns || row < 0 || row >= rows) continue;
    occupied[static_cast<std::size_t>(row) * columns + column] = true;
  }
  return static_cast<double>(std::count(occupied.begin(), occupied.end(), true)) /
         static_cast<double>(occupied.size());
}

}  // namespace lumaslam::feature
