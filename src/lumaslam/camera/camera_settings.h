#pragma once
// A camera as the settings file describes it (Camera.*, Camera1.*, Camera2.*, Stereo.*;
// docs/settings.md): intrinsics, distortion, image size and, for a stereo pair, the second
// camera and its pose. The one camera description: io::Settings reads it from a settings file,
// the dataset readers from a dataset's own calibration (io::CalibrationHint); camera/ builds
// its models from it.
#include <array>
#include <optional>
#include <string_view>

#include "lumaslam/core/pose.h"

namespace lumaslam::camera {

// Pinhole: radial-tangential distortion, stereo pairs need rectification (Camera2 + T_c1_c2).
// Rectified: undistorted, row-aligned stereo pair (KITTI); only camera 1 and Stereo.b are read.
enum class CameraModel { Pinhole, Rectified };

std::string_view toString(CameraModel model);  // "PinHole", "Rectified"

struct ImageSize {
  int width = 0;
  int height = 0;
  friend bool operator==(const ImageSize&, const ImageSize&) = default;
};

struct CameraSettings {
  CameraModel model = CameraModel::Pinhole;
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  // OpenCV order k1, k2, p1, p2, k3 (radial-tangential), all zero for Rectified.
  std::array<double, 5> distortion{};
  ImageSize size;                     // size of the images as read from the dataset
  std::optional<ImageSize> resizeTo;  // Camera.newWidth/newHeight: images are resized first
  double fps = 30.0;
  // Camera.RGB: colour images handed to the System API are RGB (1) or BGR (0, default, as
  // ORB-SLAM3). Image files are decoded by OpenCV in BGR whatever the key says.
  bool rgb = false;

  bool hasDistortion() const;
  // The calibration of the images after the optional resize (intrinsics scaled, resizeTo
  // cleared); distortion is unchanged because it acts on normalised coordinates.
  CameraSettings atWorkingSize() const;
};

struct StereoSettings {
  double baseline = 0.0;  // metres (Stereo.b, or Camera.bf / fx, or |t| of T_c1_c2)
  // Stereo.T_c1_c2: pose of camera 2 in camera 1 (maps camera-2 points into camera 1).
  // Identity rotation with t = (baseline, 0, 0) for a Rectified pair.
  SE3 T_c1_c2 = SE3::Identity();
  // Camera2.*: only for an unrectified (Pinhole) pair; rectify with camera::StereoRectifier.
  std::optional<CameraSettings> right;
};

}  // namespace lumaslam::camera
