#pragma once
// Camera 1 of the settings file (io::CameraSettings) as settings lines in the new ORB-SLAM3
// names (`lumaslam run --print-settings`, docs/settings.md), which loadSettings reads back to
// the same values. Camera2.*, Stereo.* and RGBD.* are not printed.
#include <string>

#include "lumaslam/io/settings.h"

namespace lumaslam::io {

// Camera.type, Camera1.fx/fy/cx/cy (and k1, k2, p1, p2, k3 for PinHole), Camera.width/height,
// Camera.newWidth/newHeight when set, Camera.fps, Camera.RGB: the calibrated camera as read,
// before any resize.
std::string printCameraSettings(const CameraSettings& camera);

}  // namespace lumaslam::io
