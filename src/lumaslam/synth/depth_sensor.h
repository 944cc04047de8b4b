#pragma once
// Kinect-v1-like depth: range limits, axial noise growing with z^2 (Nguyen et al., 3DIMPVT
// 2012), holes along depth discontinuities and a few random dropout blobs.
#include <cstdint>

#include <opencv2/core.hpp>

namespace lumaslam::synth {

struct DepthSensorModel {
  float min_depth_m = 0.4f;
  float max_depth_m = 5.0f;
  bool noise = true;
  float edge_hole_probability = 0.7f;
  float dropout_blobs_per_megapixel = 25.0f;
};

// `depth_m` CV_32F true z-depth; returns CV_32F metres with 0 where the sensor has no reading.
cv::Mat simulateDepthSensor(const cv::Mat& depth_m, const DepthSensorModel& model,
                            std::uint64_t key);

}  // namespace lumaslam::synth
