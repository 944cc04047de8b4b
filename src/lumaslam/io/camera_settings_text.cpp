#include "lumaslam/io/camera_settings_text.h"

#include "lumaslam/core/settings_section.h"

namespace lumaslam::io {
namespace {

std::string intrinsicsLines(const CameraSettings& camera) {
  core::SectionPrinter keys("Camera1");
  keys("fx", camera.fx);
  keys("fy", camera.fy);
  keys("cx", camera.cx);
  keys("cy", camera.cy);
  if (camera.model == CameraModel::Pinhole) {
    const char* names[] = {"k1", "k2", "p1", "p2", "k3"};
    for (std::size_t i = 0; i < camera.distortion.size(); ++i) {
      keys(names[i], camera.distortion[i]);
    }
  }
  return keys.text();
}

}  // namespace

std::string printCameraSettings(const CameraSettings& camera) {
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
  return keys.text() + intrinsicsLines(camera);
}

}  // namespace lumaslam::io
