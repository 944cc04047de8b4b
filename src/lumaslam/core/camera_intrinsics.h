#pragma once
// The pinhole that keyframes, matchers and optimisers project with: ideal (undistorted) pixels;
// stereo/RGB-D adds bf, the baseline times fx, so that the right image's column is
// u_r = u - bf / z. camera::PinholeCamera is the full model (image size, distortion).
namespace lumaslam {

struct CameraIntrinsics {
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  double bf = 0.0;  // baseline * fx [px * m]; only used by stereo observations
};

}  // namespace lumaslam
