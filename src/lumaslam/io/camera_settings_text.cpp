#include "lumaslam/io/camera_settings_text.h"

#include <fmt/format.h>

#include "lumaslam/core/settings_section.h"

namespace lumaslam::io {
namespace {

std::string intrinsicsLines(const camera::CameraSettings& camera, const std::string& section) {
  core::SectionPrinter keys(section);
  keys("fx", camera.fx);
  keys("fy", camera.fy);
  keys("cx", camera.cx);
  keys("cy", camera.cy);
  if (camera.model == camera::CameraModel::Pinhole) {
    const char* names[] = {"k1", "k2", "p1", "p2", "k3"};
    for (std::size_t i = 0; i < camera.distortion.size(); ++i) {
      keys(names[i], camera.distortion[i]);
    }
  }
  return keys.text();
}

// fmt's shortest round-trip form, always a real ("-0.0", not "-0", which would read as 0).
std::string realText(double value) {
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

// The file's own 4x4 values, so that they read back to the same snapped rotation.
std::string poseMatrixLines(const core::SettingsFile& file, const std::string& key) {
  const cv::Mat m = file.getMatrix(key, 4, 4);
  std::string data;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      data += (data.empty() ? "" : ", ") + realText(m.at<double>(r, c));
    }
  }
  return fmt::format("{}: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n  data: [{}]\n", key,
                     data);
}

}  // namespace

std::string printCameraSettings(const camera::CameraSettings& camera) {
  core::SectionPrinter keys("Camera");
  keys("type", std::string(toString(camera.model)));
  keys("width", camera.size.width);
  keys("height", camera.size.height);
  if (camera.resizeTo) {
    keys("newWidth", camera.resizeTo->width);
    keys("newHeight", camera.resizeTo->height);
  }
  keys("fps", camera.fps);
  keys("RGB", camera.rgb);
  return keys.text() + intrinsicsLines(camera, "Camera1");
}

std::string printStereoSettings(const Settings& settings) {
  if (settings.sensor == SensorType::Monocular || !settings.stereo) return {};
  std::string text;
  const auto& right = settings.stereo->right;
  if (right) text += intrinsicsLines(*right, "Camera2");
  core::SectionPrinter stereo("Stereo");
  stereo("b", settings.stereo->baseline);
  stereo("ThDepth", settings.depth.thDepth);
  text += stereo.text();
  if (right && settings.file) text += poseMatrixLines(*settings.file, "Stereo.T_c1_c2");
  if (settings.sensor == SensorType::Rgbd) {
    core::SectionPrinter rgbd("RGBD");
    rgbd("DepthMapFactor", settings.depth.depthMapFactor);
    text += rgbd.text();
  }
  return text;
}

}  // namespace lumaslam::io
