#include "lumaslam/feature/grid_fast.h"

#include <algorithm>
#include <cmath>

#include <opencv2/features2d.hpp>

namespace lumaslam::feature {

namespace {
constexpr int kFastRing = 3;  // FAST needs 3 px around a pixel
}

cv::Rect2f detectionArea(cv::Size imageSize) {
  const int border = kEdgeThreshold - kFastRing;
  return cv::Rect2f(static_cast<float>(border), static_cast<float>(border),
                    static_cast<float>(imageSize.width - 2 * border),
                    static_cast<float>(imageSize.height - 2 * border));
}

std::vector<cv::KeyPoint> detectFastInCells(const cv::Mat& image, int initialThreshold,
                                            int fallbackThreshold) {
  std::vector<cv::KeyPoint> corners;
  const int minBorder = kEdgeThreshold - kFastRing;
  const int width = image.cols - 2 * minBorder;
  const int height = image.rows - 2 * minBorder;
  if (width <= 2 * kFastRing || height <= 2 * kFastRing) return corners;

  // One FAST pass at the fallback threshold instead of one or two cv::FAST calls per cell
  // (ORB-SLAM's way), which costs more in call overhead than in corner tests. The result is
  // the same: a FAST corner's response is its score, so the corners a cell would get at
  // initialThreshold are exactly its low-threshold corners with response >= initialThreshold
  // (non-max suppression only ever removes a corner in favour of a stronger one).
  std::vector<cv::KeyPoint> candidates;
  cv::FAST(image(cv::Rect(minBorder, minBorder, width, height)), candidates, fallbackThreshold,
           true);

  const int columns = std::max(1, width / kFastCellSize);
  const int rows = std::max(1, height / kFastCellSize);
  const int cellWidth = (width + columns - 1) / columns;
  const int cellHeight = (height + rows - 1) / rows;
  const auto cellOf = [&](const cv::KeyPoint& corner) {
    // Corners lie in [kFastRing, size - kFastRing) of the region; cell c owns
    // [c * cellSize + kFastRing, (c + 1) * cellSize + kFastRing), as ORB-SLAM's cell regions.
    const int column = std::min(static_cast<int>(corner.pt.x - kFastRing) / cellWidth, columns - 1);
    const int row = std::min(static_cast<int>(corner.pt.y - kFastRing) / cellHeight, rows - 1);
    return row * columns + column;
  };
  std::vector<bool> cellHasStrongCorner(static_cast<std::size_t>(columns) * rows, false);
  for (const cv::KeyPoint& corner : candidates) {
    if (corner.response >= initialThreshold) cellHasStrongCorner[cellOf(corner)] = true;
  }
  corners.reserve(candidates.size());
  for (cv::KeyPoint& corner : candidates) {
    if (cellHasStrongCorner[cellOf(corner)] && corner.response < initialThreshold) continue;
    corner.pt.x += static_cast<float>(minBorder);
    corner.pt.y += static_cast<float>(minBorder);
    corners.push_back(corner);
  }
  return corners;
}

}  // namespace lumaslam::feature
