#include "lumaslam/camera/camera_settings.h"

namespace lumaslam::camera {

std::string_view toString(CameraModel model) {
  return model == CameraModel::Pinhole ? "PinHole" : "Rectified";
}

bool CameraSettings::hasDistortion() const {
  for (const double d : distortion) {
    if (d != 0.0) return true;
  }
  return false;
}

CameraSettings CameraSettings::atWorkingSize() const {
  CameraSettings out = *this;
  if (!resizeTo) return out;
  const double sx = static_cast<double>(resizeTo->width) / size.width;
  const double sy = static_cast<double>(resizeTo->height) / size.height;
  out.fx *= sx;
  out.cx *= sx;
  out.fy *= sy;
  out.cy *= sy;
  out.size = *resizeTo;
  out.resizeTo.reset();
  return out;
}

}  // namespace lumaslam::camera
