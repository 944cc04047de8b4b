#pragma once
// Kinect-v1-like depth: range limits, axial noise growing with z^2 and, near grazing view
// angles, with the angle (Nguyen, Izadi & Lovell, 3DIMPVT 2012), disparity quantisation in
// 1/8-pixel steps, so the depth resolution falls with z^2 (Khoshelham & Elberink, Sensors 2012),
// holes along depth discontinuities, holes where the projected IR pattern does not come back
// (very dark surfaces, grazing view angles), a few random dropout blobs, and an imperfect
// registration of the depth image to the colour image.
#include <cstdint>

#include <opencv2/core.hpp>

namespace lumaslam::synth {

struct DepthSensorModel {
  float min_depth_m = 0.4f;
  float max_depth_m = 5.0f;
  bool noise = true;
  float edge_hole_probability = 0.7f;
  float dropout_blobs_per_megapixel = 25.0f;

  // Everything below is off by default (the presets before issue 15 render as they did).
  // No reading below this linear IR reflectance (the speckles drown in the sensor's noise
  // floor; black plastic, dark cloth, monitors), some readings up to twice it. 0 = off.
  float min_ir_albedo = 0.0f;
  // No reading beyond this angle between the ray and the surface normal (the speckles smear
  // out and cannot be matched), some from 5 degrees before it. >= 90 = off.
  float max_incidence_deg = 90.0f;
  // Nguyen et al.'s extra axial noise near grazing angles: 0.1 mm / sqrt(z) theta^2 /
  // (pi/2 - theta)^2.
  bool grazing_noise = false;
  // Disparity steps of 1/8 pixel at focal length x baseline = 580 px x 7.5 cm: ~3 mm at 1 m,
  // ~11 mm at 2 m, ~46 mm at 4 m (what the Kinect v1's 11-bit disparity gives).
  bool quantize_disparity = false;
  // Registration error of depth to colour: the depth image is the ideal registered one scaled
  // by `registration_scale` about the image centre, then shifted by `registration_shift_px`
  // (so an edge at colour column u sits at depth column u + shift.x for scale 1). Factory
  // calibrations of the Kinect v1 leave 1-2 pixels.
  cv::Point2f registration_shift_px{0.0f, 0.0f};
  float registration_scale = 1.0f;
  // Unsynchronised streams: each depth frame is captured at the colour frame's timestamp plus
  // a per-frame offset uniform in +-max (Kinect v1: up to half a frame). At most 15 ms, so that
  // depth stamps keep increasing and pair with their own colour frame within TUM's 20 ms.
  double max_time_offset_ms = 0.0;
};

// What the sensor looks at, registered to the colour image: `depth_m` CV_32F true z-depth,
// optional (empty) CV_32F `ir_albedo` and `incidence_cos` maps (see RenderedView).
struct DepthSensorInput {
  cv::Mat depth_m;
  cv::Mat ir_albedo;
  cv::Mat incidence_cos;
};

// Returns CV_32F metres with 0 where the sensor has no reading.
cv::Mat simulateDepthSensor(const DepthSensorInput& input, const DepthSensorModel& model,
                            std::uint64_t key);
cv::Mat simulateDepthSensor(const cv::Mat& depth_m, const DepthSensorModel& model,
                            std::uint64_t key);

}  // namespace lumaslam::synth
