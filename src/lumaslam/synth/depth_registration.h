#pragma once
// Depth-to-colour misregistration (see DepthSensorModel::registration_*): every map of a
// DepthSensorInput is resampled with the same scale about the image centre and shift, by
// nearest neighbour, because interpolating depth across an object's edge would invent
// surfaces between it and the background. Pixels that come from outside the image have no
// reading (depth 0), like the invalid border of a registered Kinect image.
#include <opencv2/core.hpp>

#include "lumaslam/synth/depth_sensor.h"

namespace lumaslam::synth {

DepthSensorInput misregister(const DepthSensorInput& input, cv::Point2f shift_px, float scale);

}  // namespace lumaslam::synth
