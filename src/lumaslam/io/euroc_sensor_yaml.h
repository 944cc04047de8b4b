#pragma once
// EuRoC ASL camera description (mav0/camN/sensor.yaml): intrinsics, distortion, resolution,
// rate and T_BS (sensor to body). Original EuRoC files lack the %YAML header and use flow
// lists; core::SettingsFile adds the header so cv::FileStorage reads them.
#include <filesystem>

#include "lumaslam/io/dataset_reader.h"

namespace lumaslam::io {

// Throws Error naming the file and key for a missing file, a missing key, a camera model other
// than pinhole, wrong list lengths or a T_BS that is not a rigid transform.
CameraCalibration readEurocCameraYaml(const std::filesystem::path& file);

}  // namespace lumaslam::io
