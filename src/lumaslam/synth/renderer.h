#pragma once
// Ray casting of a SceneSnapshot through a pinhole camera: analytic ray/box and ray/billboard
// intersection per pixel (rows in parallel), trilinear texture lookup by pixel footprint and
// Lambertian shading from the scene's lights. No GPU needed. A rolling shutter renders each
// row from its own pose (the scene itself is taken at one time per image).
#include <opencv2/core.hpp>

#include "lumaslam/core/pose.h"
#include "lumaslam/synth/camera_rig.h"
#include "lumaslam/synth/rolling_shutter.h"
#include "lumaslam/synth/scene.h"

namespace lumaslam::synth {

struct RenderedView {
  cv::Mat radiance;    // CV_32FC3, linear BGR (1 = a white surface under nominal light)
  cv::Mat depth;       // CV_32F, z-depth in metres (every pixel hits the closed room)
  cv::Mat object_ids;  // CV_8U, 0 = static scene, else the dynamic object's id
  // What an active depth sensor's return depends on (see depth_sensor.h):
  cv::Mat ir_albedo;      // CV_32F, linear reflectance of the surface (mean of the channels)
  cv::Mat incidence_cos;  // CV_32F, cosine between the viewing ray and the surface normal
};

RenderedView renderView(const Scene& scene, const SceneSnapshot& snapshot,
                        const PinholeCamera& camera, const SE3& T_w_c);
RenderedView renderView(const Scene& scene, const SceneSnapshot& snapshot,
                        const PinholeCamera& camera, const RowPoses& row_poses);

}  // namespace lumaslam::synth
