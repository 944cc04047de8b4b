#pragma once
// FAST corners with a per-cell threshold (30x30 px cells, ORB-SLAM's scheme): a cell keeps its
// corners of the high threshold, and only a cell with none falls back to the low threshold,
// so low-contrast regions still get candidates for the quadtree distribution.
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::feature {

// Keypoints are kept at least this far from the image border (orientation patch radius 15,
// rotated BRIEF pattern reaches 13*sqrt(2) < 19).
inline constexpr int kEdgeThreshold = 19;
inline constexpr int kFastCellSize = 30;

// The area in which keypoints may lie, [kEdgeThreshold, size - kEdgeThreshold), extended by
// FAST's 3-px ring on each side (the region handed to the quadtree, as ORB-SLAM).
cv::Rect2f detectionArea(cv::Size imageSize);

// FAST (non-max suppressed) corners in `image` (CV_8UC1), in image coordinates, all at least
// kEdgeThreshold px from the border. Empty if the image is too small.
std::vector<cv::KeyPoint> detectFastInCells(const cv::Mat& image, int initialThreshold,
                                            int fallbackThreshold);

}  // namespace lumaslam::feature
