#pragma once
// Moves boxes detected on one frame onto the next frame by sparse optical flow, for the
// frames a strided detector skips.
#include <opencv2/core.hpp>

#include "lumaslam/detect/detection.h"
#include "lumaslam/detect/detector_params.h"

namespace lumaslam::detect {

// Each box follows the Lucas-Kanade flow (cv::calcOpticalFlowPyrLK) of good features
// (cv::goodFeaturesToTrack) in its central part, then is clipped to the image:
// - scale: the median ratio of distances between tracked features after / before, over pairs
//   not too close together, applied about the box's centre only when at least 90 % of the
//   pairs agree the box grew (or shrank), when it differs from 1 by 0.5 % or more, and when at
//   least params.min_scale_tracked features were tracked; clamped to params.max_scale_step;
// - shift: the median over features of their flow less the scaling about the box's centre
//   (with no scaling: the median flow, so a pure shift moves the box exactly as before).
// A box with fewer than params.min_tracked tracked features stays where it was.
// Images: 8-bit, same size, gray or BGR.
Detections propagateDetections(const cv::Mat& previous, const cv::Mat& next,
                               const Detections& detections, const PropagationParams& params);

}  // namespace lumaslam::detect
