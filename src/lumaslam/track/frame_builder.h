#pragma once
// Turns an image (plus depth for RGB-D) into a Frame: ORB features outside the dynamic mask,
// undistorted keypoints, a feature grid, and per-feature depth / virtual right coordinate
// u_r = u - bf / z (ORB-SLAM's ComputeStereoFromRGBD).
#include <memory>

#include <opencv2/core.hpp>

#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/map/scale_pyramid.h"
#include "lumaslam/track/frame.h"
#include "lumaslam/track/frame_camera.h"

namespace lumaslam::track {

class FrameBuilder {
 public:
  FrameBuilder(const FrameCamera& camera, const feature::OrbSettings& orb);

  // `gray` CV_8UC1; `depth_m` empty or CV_32FC1 metres (0 / NaN = no depth) of the same size;
  // `mask` empty or CV_8UC1, nonzero = dynamic (no features there).
  Frame build(std::size_t index, double timestamp, const cv::Mat& gray, const cv::Mat& depth_m,
              const cv::Mat& mask = cv::Mat()) const;

  const FrameCamera& camera() const { return camera_; }
  const feature::OrbExtractor& extractor() const { return extractor_; }
  const std::shared_ptr<const map::ScalePyramid>& pyramid() const { return pyramid_; }

 private:
  FrameCamera camera_;
  feature::OrbExtractor extractor_;
  std::shared_ptr<const map::ScalePyramid> pyramid_;
  cv::Rect2f bounds_;
};

}  // namespace lumaslam::track
