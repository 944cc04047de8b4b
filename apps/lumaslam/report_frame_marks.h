#pragma once
// The "as tracked" sample frame of `lumaslam report`: the enhanced image scaled down, its ORB
// keypoints green and, from the run's moving_features.txt, the detection boxes and the
// features the run dropped red (circles: inside a box, crosses: flagged by the motion test).
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "moving_features_file.h"

namespace lumaslam::cli {

struct DrawnFrame {
  cv::Mat canvas;
  std::size_t green = 0;  // keypoints drawn green
};

// `colour` (8-bit gray or BGR) scaled down to at most `max_width` pixels wide, with the marks
// drawn after the downscale so that they keep their size. `marks` (may be null) are in pixels
// of an image of `marks_image` size, stretched to `colour`'s; a keypoint whose position,
// rounded to those pixels, is a red mark's is the run's dropped feature there and is not drawn
// green.
DrawnFrame drawFrameMarks(const cv::Mat& colour, const std::vector<cv::KeyPoint>& keypoints,
                          const FrameMarks* marks, cv::Size marks_image, int max_width);

}  // namespace lumaslam::cli
