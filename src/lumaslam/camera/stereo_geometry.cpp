#include "lumaslam/camera/stereo_geometry.h"

#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/core/error.h"

namespace lumaslam::camera {

StereoGeometry::StereoGeometry(double bf, double baseline, double thDepth)
    : bf_(bf), baseline_(baseline), closeDepth_(thDepth * baseline) {
  if (!(bf > 0.0) || !(baseline > 0.0) || !(thDepth > 0.0)) {
    fail("StereoGeometry: bf, baseline and ThDepth must be > 0, got bf={} b={} ThDepth={}", bf,
         baseline, thDepth);
  }
}

StereoGeometry StereoGeometry::fromSettings(const CameraSettings& camera,
                                            const StereoSettings& stereo, double thDepth) {
  if (stereo.right) {
    fail(
        "unrectified stereo pair (Camera2.*): bf is known only after rectification, "
        "use StereoGeometry::fromRectifier");
  }
  return StereoGeometry(stereo.baseline * camera.atWorkingSize().fx, stereo.baseline, thDepth);
}

StereoGeometry StereoGeometry::fromRectifier(const StereoRectifier& rectifier, double thDepth) {
  return StereoGeometry(rectifier.bf(), rectifier.baseline(), thDepth);
}

cv::Mat depthToMetres(const cv::Mat& raw, double depthMapFactor) {
  if (raw.empty()) fail("depthToMetres: empty depth image");
  if (raw.channels() != 1 || (raw.depth() != CV_16U && raw.depth() != CV_32F)) {
    fail("depthToMetres: expected a one-channel 16-bit or float depth image, got type {}",
         cv::typeToString(raw.type()));
  }
  if (!(depthMapFactor > 0.0))
    fail("depthToMetres: DepthMapFactor must be > 0, got {}", depthMapFactor);
  cv::Mat metres;
  raw.convertTo(metres, CV_32F, 1.0 / depthMapFactor);
  cv::patchNaNs(metres, 0.0);  // float depth from ROS bags marks holes with NaN
  return metres;
}

}  // namespace lumaslam::camera
