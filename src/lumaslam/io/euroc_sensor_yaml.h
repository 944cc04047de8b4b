#pragma once
// EuRoC ASL camera description (mav0/camN/sensor.yaml): intrinsics, distortion, resolution,
// rate and T_BS (sensor to body). Original EuRoC files lack the %YAML header and use flow
// lists; core::SettingsFile adds the header so cv::FileStorage reads them.
#include <filesystem>

#include <optional>
#include <string>

#include "lumaslam/camera/camera_settings.h"
#include "lumaslam/core/pose.h"

namespace lumaslam::io {

struct EurocCamera {
  // Pinhole with the radial-tangential coefficients k1 k2 p1 p2 [k3] ("none": all zero);
  // nullopt for a distortion model camera/ has no model for (e.g. TUM-VI's "equidistant"):
  // such a dataset still reads, it only offers no calibration hint.
  std::optional<camera::CameraSettings> camera;
  std::string distortion_model;      // as the file names it
  SE3 T_body_cam = SE3::Identity();  // T_BS; identity when the file has none
};

// Throws Error naming the file and key for a missing file, a missing key, a camera model other
// than pinhole, wrong list lengths or a T_BS that is not a rigid transform.
EurocCamera readEurocCameraYaml(const std::filesystem::path& file);

}  // namespace lumaslam::io
