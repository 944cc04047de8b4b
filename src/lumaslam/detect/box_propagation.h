#pragma once
// Moves boxes detected on one frame onto the next frame by sparse optical flow, for the
// frames a strided detector skips.
#include <opencv2/core.hpp>

#include "lumaslam/detect/detection.h"
#include "lumaslam/detect/detector_params.h"

namespace lumaslam::detect {

// Each box is shifted by the median Lucas-Kanade flow (cv::calcOpticalFlowPyrLK) of good
// features (cv::goodFeaturesToTrack) in its central part, then clipped to the image. A box
// with too few tracked features stays where it was. Images: 8-bit, same size, gray or BGR.
Detections propagateDetections(const cv::Mat& previous, const cv::Mat& next,
                               const Detections& detections, const PropagationParams& params);

}  // namespace lumaslam::detect
