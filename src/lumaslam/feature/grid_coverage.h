#pragma once
// How evenly keypoints cover an image: the fraction of cells of a columns x rows grid that
// hold at least one keypoint (1 = every cell).
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::feature {

double gridCoverage(const std::vector<cv::KeyPoint>& keypoints, cv::Size imageSize, int columns = 8,
                    int rows = 8);

}  // namespace lumaslam::feature
