#pragma once
// The left image of a frame as tracking takes it, for `lumaslam report`'s sample frames: resized
// to Camera.newWidth/newHeight and, for an unrectified stereo pair (Camera2.*), rectified, in
// the Pipeline's order. moving_features.txt's positions are pixels of this image, so marks
// drawn on it land where the run found them.
#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "lumaslam/io/settings.h"

namespace lumaslam::camera {
class StereoRectifier;
}

namespace lumaslam::cli {

class TrackedImage {
 public:
  // Throws Error when an unrectified pair's calibration cannot be rectified.
  explicit TrackedImage(const io::Settings& settings);
  ~TrackedImage();
  TrackedImage(TrackedImage&&) noexcept;
  TrackedImage& operator=(TrackedImage&&) noexcept;

  // `as_read`: the left (or only) image as the dataset gives it.
  cv::Mat of(const cv::Mat& as_read) const;
  // What is done to the image, e.g. "resized to 320x240, rectified"; empty for nothing.
  std::string description() const;

 private:
  cv::Size calibrated_;
  cv::Size working_;  // empty without Camera.newWidth/newHeight
  std::unique_ptr<camera::StereoRectifier> rectifier_;
};

}  // namespace lumaslam::cli
