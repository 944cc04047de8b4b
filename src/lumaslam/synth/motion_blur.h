#pragma once
// Motion blur from the camera's own motion during the exposure: every pixel integrates the
// sharp mid-exposure image along the path its scene point takes between the poses at the
// start and the end of the exposure (computed from the pixel's depth; static-scene flow). With
// a rolling shutter every row has its own exposure interval, hence its own three poses.
#include <opencv2/core.hpp>

#include "lumaslam/core/pose.h"
#include "lumaslam/synth/camera_rig.h"
#include "lumaslam/synth/rolling_shutter.h"

namespace lumaslam::synth {

// `radiance` CV_32FC3 and `depth` CV_32F rendered at T_w_mid; returns the blurred radiance.
cv::Mat applyMotionBlur(const cv::Mat& radiance, const cv::Mat& depth, const PinholeCamera& camera,
                        const SE3& T_w_mid, const SE3& T_w_start, const SE3& T_w_end);
// The same with the poses of each row (rolling shutter).
cv::Mat applyMotionBlur(const cv::Mat& radiance, const cv::Mat& depth, const PinholeCamera& camera,
                        const RowPoses& T_w_mid, const RowPoses& T_w_start,
                        const RowPoses& T_w_end);

}  // namespace lumaslam::synth
