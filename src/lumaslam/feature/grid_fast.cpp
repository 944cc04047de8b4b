#include "lumaslam/feature/grid_fast.h"

#include <algorithm>
#include <cmath>

#include <opencv2/features2d.hpp>

namespace lumaslam::feature {

namespace {

constexpr int kFastRing = 3;  // FAST needs 3 px around a pixel

// Above this share of fallback cells one low-threshold pass over the whole level is cheaper
// than a high-threshold pass plus low-threshold passes over the fallback cells (callgrind:
// the second way costs 46% fewer instructions on textured synthetic frames, 18% fewer on
// EuRoC with 60% fallback cells, about as many at 80% and 22% more at 88%).
constexpr double kMaxFallbackShareForTwoPasses = 0.75;

// The cells of the FAST region (the image minus minBorder on each side). Corners lie in
// [kFastRing, size - kFastRing) of the region; cell c owns [c * cellSize + kFastRing,
// (c + 1) * cellSize + kFastRing), as ORB-SLAM's cell regions, the last one up to the end.
struct CellLayout {
  int width, height, columns, rows, cellWidth, cellHeight;

  CellLayout(int regionWidth, int regionHeight)
      : width(regionWidth),
        height(regionHeight),
        columns(std::max(1, regionWidth / kFastCellSize)),
        rows(std::max(1, regionHeight / kFastCellSize)),
        cellWidth((regionWidth + columns - 1) / columns),
        cellHeight((regionHeight + rows - 1) / rows) {}

  int count() const { return columns * rows; }
  int columnOf(float x) const {
    return std::min(static_cast<int>(x - kFastRing) / cellWidth, columns - 1);
  }
  int rowOf(float y) const {
    return std::min(static_cast<int>(y - kFastRing) / cellHeight, rows - 1);
  }
  int cellOf(const cv::KeyPoint& corner) const {
    return rowOf(corner.pt.y) * columns + columnOf(corner.pt.x);
  }
  // First corner coordinate of column/row c, and one past the last.
  int columnBegin(int c) const { return c * cellWidth + kFastRing; }
  int columnEnd(int c) const {
    return c == columns - 1 ? width - kFastRing : std::min(width - kFastRing, columnBegin(c + 1));
  }
  int rowBegin(int r) const { return r * cellHeight + kFastRing; }
  int rowEnd(int r) const {
    return r == rows - 1 ? height - kFastRing : std::min(height - kFastRing, rowBegin(r + 1));
  }
};

// Low-threshold corners of the cells [firstColumn, lastColumn] of `row`, exactly as one FAST
// pass over the whole region finds them: the window adds FAST's ring plus one pixel, so the
// non-max suppression of a corner on the cell edge sees the same neighbour scores.
void detectInCellRun(const cv::Mat& region, const CellLayout& cells, int row, int firstColumn,
                     int lastColumn, int threshold, std::vector<cv::KeyPoint>& corners) {
  constexpr int kMargin = kFastRing + 1;
  const int x0 = std::max(0, cells.columnBegin(firstColumn) - kMargin);
  const int x1 = std::min(cells.width, cells.columnEnd(lastColumn) + kMargin);
  const int y0 = std::max(0, cells.rowBegin(row) - kMargin);
  const int y1 = std::min(cells.height, cells.rowEnd(row) + kMargin);
  if (x1 - x0 <= 2 * kFastRing || y1 - y0 <= 2 * kFastRing) return;
  std::vector<cv::KeyPoint> found;
  cv::FAST(region(cv::Rect(x0, y0, x1 - x0, y1 - y0)), found, threshold, true);
  for (cv::KeyPoint& corner : found) {
    corner.pt.x += static_cast<float>(x0);
    corner.pt.y += static_cast<float>(y0);
    const int column = cells.columnOf(corner.pt.x);
    if (cells.rowOf(corner.pt.y) == row && column >= firstColumn && column <= lastColumn) {
      corners.push_back(corner);
    }
  }
}

}  // namespace

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
  const cv::Mat region = image(cv::Rect(minBorder, minBorder, width, height));
  const CellLayout cells(width, height);

  // Whole-region FAST passes instead of one or two cv::FAST calls per cell (ORB-SLAM's way,
  // which costs more in call overhead than in corner tests), with the same result: a FAST
  // corner's response is its score, independent of the threshold, and non-max suppression
  // only ever removes a corner in favour of a stronger one. So the high-threshold pass finds
  // exactly the low-threshold corners with response >= initialThreshold, and the cells it
  // leaves empty take their low-threshold corners from a second pass over just those cells.
  std::vector<cv::KeyPoint> strong;
  cv::FAST(region, strong, initialThreshold, true);
  std::vector<bool> cellHasStrongCorner(static_cast<std::size_t>(cells.count()), false);
  for (const cv::KeyPoint& corner : strong) cellHasStrongCorner[cells.cellOf(corner)] = true;
  const auto fallbackCells =
      std::count(cellHasStrongCorner.begin(), cellHasStrongCorner.end(), false);

  if (fallbackCells > kMaxFallbackShareForTwoPasses * cells.count()) {
    std::vector<cv::KeyPoint> candidates;
    cv::FAST(region, candidates, fallbackThreshold, true);
    corners.reserve(candidates.size());
    for (const cv::KeyPoint& corner : candidates) {
      if (cellHasStrongCorner[cells.cellOf(corner)] && corner.response < initialThreshold) continue;
      corners.push_back(corner);
    }
  } else {
    std::vector<cv::KeyPoint> weak;
    for (int row = 0; row < cells.rows; ++row) {
      for (int column = 0; column < cells.columns;) {
        if (cellHasStrongCorner[row * cells.columns + column]) {
          ++column;
          continue;
        }
        int last = column;
        while (last + 1 < cells.columns && !cellHasStrongCorner[row * cells.columns + last + 1]) {
          ++last;
        }
        detectInCellRun(region, cells, row, column, last, fallbackThreshold, weak);
        column = last + 1;
      }
    }
    // Raster order, as a single pass returns them (the quadtree breaks response ties by order).
    const auto rasterOrder = [](const cv::KeyPoint& a, const cv::KeyPoint& b) {
      return a.pt.y < b.pt.y || (a.pt.y == b.pt.y && a.pt.x < b.pt.x);
    };
    std::sort(weak.begin(), weak.end(), rasterOrder);
    corners.resize(strong.size() + weak.size());
    std::merge(strong.begin(), strong.end(), weak.begin(), weak.end(), corners.begin(),
               rasterOrder);
  }
  for (cv::KeyPoint& corner : corners) {
    corner.pt.x += static_cast<float>(minBorder);
    corner.pt.y += static_cast<float>(minBorder);
  }
  return corners;
}

}  // namespace lumaslam::feature
