#pragma once
// Where features must not be taken: the boxes of dynamic objects (paper section 3.2), grown
// by a margin, optionally given back to the static background seen behind a person when
// depth is known (RGB-D).
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/detect/detector_params.h"

namespace lumaslam::detect {

// CV_8U mask of image_size: 255 inside every box grown by margin_px on each side, else 0.
cv::Mat makeDynamicMask(const cv::Size& image_size, const std::vector<cv::Rect2f>& boxes,
                        int margin_px);

// The person's depth in a box: params.depth_percentile of the valid (finite, > 0) depths in
// the central params.depth_inner_fraction of the box; nullopt when none is valid.
std::optional<double> personDepth(const cv::Mat& depth_m, const cv::Rect2f& box,
                                  const MaskParams& params);

// Unmasks the pixels of each (margin-grown) box whose depth is clearly behind the person
// (> person depth + params.depth_tolerance_m): the wall behind someone keeps its features.
// Pixels without valid depth stay masked; a pixel covered by several boxes is freed only if
// it is behind the person of every box covering it, and only if it is at least
// params.depth_edge_px from every pixel that stays masked (the person's silhouette). depth_m: CV_32F metres, 0 or NaN =
// invalid, same size as mask. Throws Error for a size or type mismatch.
cv::Mat refineMaskWithDepth(const cv::Mat& mask, const cv::Mat& depth_m,
                            const std::vector<cv::Rect2f>& boxes, const MaskParams& params = {});

// Indices of the keypoints outside the mask (mask == 0 at the rounded position; points
// outside the image are kept).
std::vector<int> filterKeypoints(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& mask);

}  // namespace lumaslam::detect
