#pragma once
// The cameras of the settings file (io::Settings) as settings lines in the new ORB-SLAM3 names
// (`lumaslam run --print-settings`, docs/settings.md), which loadSettings reads back to the
// same values.
#include <string>

#include "lumaslam/io/settings.h"

namespace lumaslam::io {

// Camera.type, Camera1.fx/fy/cx/cy (and k1, k2, p1, p2, k3 for PinHole), Camera.width/height,
// Camera.newWidth/newHeight when set, Camera.fps, Camera.RGB: the calibrated camera as read,
// before any resize.
std::string printCameraSettings(const camera::CameraSettings& camera);

// What a stereo or RGB-D run reads besides camera 1: Camera2.* and Stereo.T_c1_c2 (as the file
// has it, before its rotation is snapped) for an unrectified pair, Stereo.b (the baseline as
// read), Stereo.ThDepth and, for RGB-D, RGBD.DepthMapFactor. Empty for a monocular run.
std::string printStereoSettings(const Settings& settings);

}  // namespace lumaslam::io
