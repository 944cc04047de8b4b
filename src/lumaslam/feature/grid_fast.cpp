#include "lumaslam/feature/grid_fast.h"

#include <algorithm>
#include <cmath>

#include <opencv2/features2d.hpp>

namespace lumaslam::feature {

namespace {
constexpr int kFastRing = 3;  // FAST needs 3 px around a pixel; cells overlap by 2 rings
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
  const int maxBorderX = image.cols - kEdgeThreshold + kFastRing;
  const int maxBorderY = image.rows - kEdgeThreshold + kFastRing;
  const int width = maxBorderX - minBorder;
  const int height = maxBorderY - minBorder;
  if (width <= 2 * kFastRing || height <= 2 * kFastRing) return corners;

  const int columns = std::max(1, width / kFastCellSize);
  const int rows = std::max(1, height / kFastCellSize);
  const int cellWidth = (width + columns - 1) / columns;
  const int cellHeight = (height + rows - 1) / rows;
  std::vector<cv::KeyPoint> cellCorners;
  for (int row = 0; row < rows; ++row) {
    const int y0 = minBorder + row * cellHeight;
    if (y0 >= maxBorderY - kFastRing) continue;
    // Each cell's region extends 2 rings past the next cell's start so that FAST, which
    // skips 3 px at the region border, covers every pixel exactly once.
    const int y1 = std::min(y0 + cellHeight + 2 * kFastRing, maxBorderY);
    for (int column = 0; column < columns; ++column) {
      const int x0 = minBorder + column * cellWidth;
      if (x0 >= maxBorderX - kFastRing) continue;
      const int x1 = std::min(x0 + cellWidth + 2 * kFastRing, maxBorderX);
      const cv::Mat cell = image(cv::Range(y0, y1), cv::Range(x0, x1));
      cellCorners.clear();
      cv::FAST(cell, cellCorners, initialThreshold, true);
      if (cellCorners.empty()) cv::FAST(cell, cellCorners, fallbackThreshold, true);
      for (cv::KeyPoint& corner : cellCorners) {
        corner.pt.x += static_cast<float>(x0);
        corner.pt.y += static_cast<float>(y0);
        corners.push_back(corner);
      }
    }
  }
  return corners;
}

}  // namespace lumaslam::feature
