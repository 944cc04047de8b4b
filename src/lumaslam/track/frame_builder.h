#pragma once
// Turns an image (plus depth for RGB-D, or the right image of a rectified stereo pair) into a
// Frame: ORB features outside the dynamic mask, undistorted keypoints, a feature grid, and
// per-feature depth / right coordinate: u_r = u - bf / z from the depth image (ORB-SLAM's
// ComputeStereoFromRGBD) or from stereo matches (feature::StereoMatcher).
#include <memory>
#include <optional>

#include <opencv2/core.hpp>

#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/feature/stereo_matcher.h"
#include "lumaslam/track/frame.h"
#include "lumaslam/track/frame_camera.h"

namespace lumaslam::track {

class FrameBuilder {
 public:
  // `threaded`: buildStereo extracts the right image in a thread of its own beside the left
  // one; false (System.sequential): one after the other in the caller's thread.
  FrameBuilder(const FrameCamera& camera, const feature::OrbSettings& orb, bool threaded = true);

  // `gray` CV_8UC1; `depth_m` empty or CV_32FC1 metres (0 / NaN = no depth) of the same size;
  // `mask` empty or CV_8UC1, nonzero = dynamic (no features there).
  Frame build(std::size_t index, double timestamp, const cv::Mat& gray, const cv::Mat& depth_m,
              const cv::Mat& mask = cv::Mat()) const;
  // Rectified stereo pair (camera without distortion, bf > 0): `left` and `right` CV_8UC1 of
  // the camera size, extracted concurrently (when threaded); `mask` applies to the left image.
  Frame buildStereo(std::size_t index, double timestamp, const cv::Mat& left, const cv::Mat& right,
                    const cv::Mat& mask = cv::Mat()) const;

  const FrameCamera& camera() const { return camera_; }
  const feature::OrbExtractor& extractor() const { return extractor_; }
  const std::shared_ptr<const feature::ScaleLevels>& pyramid() const { return pyramid_; }

 private:
  void checkImage(std::size_t index, const cv::Mat& gray, const char* what) const;
  // Feature set with keypoints, descriptors and undistorted points; no depth yet.
  std::shared_ptr<map::FeatureSet> featureSetFrom(feature::OrbFeatures&& extracted) const;
  Frame frameFrom(std::size_t index, double timestamp,
                  std::shared_ptr<map::FeatureSet> features) const;

  FrameCamera camera_;
  feature::OrbExtractor extractor_;
  std::optional<feature::StereoMatcher> stereo_matcher_;  // when bf > 0
  std::shared_ptr<const feature::ScaleLevels> pyramid_;
  cv::Rect2f bounds_;
  bool threaded_ = true;
};

}  // namespace lumaslam::track
