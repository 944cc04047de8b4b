#pragma once
// Surface textures: an image per face with a Gaussian mip pyramid, sampled trilinearly with a
// level chosen from the pixel footprint so that distant or oblique surfaces do not alias
// (aliasing makes ORB corners flicker from frame to frame, which real cameras do not do).
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::synth {

class MipTexture {
 public:
  // `image` is CV_8UC3 (BGR, display-encoded); `texel_size_m` is the size of one texel on the
  // surface in metres.
  MipTexture(const cv::Mat& image, float texel_size_m);

  float texelSize() const { return texel_size_; }
  int width() const { return levels_.front().cols; }
  int height() const { return levels_.front().rows; }
  const cv::Mat& level(int i) const { return levels_[static_cast<size_t>(i)]; }
  int levelCount() const { return static_cast<int>(levels_.size()); }

  // Albedo (BGR, display-encoded 0..1) at surface coordinates (u, v) in metres; `footprint_m`
  // is the size of one image pixel on the surface.
  cv::Vec3f sample(float u_m, float v_m, float footprint_m) const;

 private:
  std::vector<cv::Mat> levels_;
  float texel_size_;
  float inv_texel_size_;
};

}  // namespace lumaslam::synth
