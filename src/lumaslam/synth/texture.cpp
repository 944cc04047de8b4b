#include "lumaslam/synth/texture.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::synth {

MipTexture::MipTexture(const cv::Mat& image, float texel_size_m)
    : texel_size_(texel_size_m), inv_texel_size_(1.0f / texel_size_m) {
  if (image.empty() || image.type() != CV_8UC3)
    fail("MipTexture: expected a non-empty CV_8UC3 image");
  if (!(texel_size_m > 0.0f)) fail("MipTexture: texel size must be positive, got {}", texel_size_m);
  levels_.push_back(image.clone());
  while (levels_.back().cols > 4 && levels_.back().rows > 4) {
    cv::Mat next;
    cv::pyrDown(levels_.back(), next);
    levels_.push_back(std::move(next));
  }
}

cv::Vec3f MipTexture::bilinear(int level, float x, float y) const {
  const cv::Mat& img = levels_[static_cast<size_t>(level)];
  x = std::clamp(x, 0.0f, static_cast<float>(img.cols - 1));
  y = std::clamp(y, 0.0f, static_cast<float>(img.rows - 1));
  const int x0 = std::min(static_cast<int>(x), img.cols - 2 < 0 ? 0 : img.cols - 2);
  const int y0 = std::min(static_cast<int>(y), img.rows - 2 < 0 ? 0 : img.rows - 2);
  const int x1 = std::min(x0 + 1, img.cols - 1);
  const int y1 = std::min(y0 + 1, img.rows - 1);
  const float fx = x - static_cast<float>(x0);
  const float fy = y - static_cast<float>(y0);
  const auto* row0 = img.ptr<cv::Vec3b>(y0);
  const auto* row1 = img.ptr<cv::Vec3b>(y1);
  cv::Vec3f out;
  for (int c = 0; c < 3; ++c) {
    const float top = row0[x0][c] + fx * (static_cast<float>(row0[x1][c]) - row0[x0][c]);
    const float bottom = row1[x0][c] + fx * (static_cast<float>(row1[x1][c]) - row1[x0][c]);
    out[c] = top + fy * (bottom - top);
  }
  return out * (1.0f / 255.0f);
}

cv::Vec3f MipTexture::sample(float u_m, float v_m, float footprint_m) const {
  const float footprint_texels = footprint_m * inv_texel_size_;
  // log2 by exponent + linear mantissa (error < 0.09 levels; plenty for a level of detail).
  int exponent = 0;
  const float mantissa = footprint_texels > 1.0f ? std::frexp(footprint_texels, &exponent) : 0.5f;
  const float lod =
      footprint_texels > 1.0f ? static_cast<float>(exponent - 1) + 2.0f * mantissa - 1.0f : 0.0f;
  const int max_level = levelCount() - 1;
  const int l0 = std::min(static_cast<int>(lod), max_level);
  const int l1 = std::min(l0 + 1, max_level);
  // "Brilinear": one level for the first half of each octave, a blend over the second half.
  const float blend = std::clamp(2.0f * (lod - static_cast<float>(l0)) - 1.0f, 0.0f, 1.0f);
  const float x = u_m * inv_texel_size_;
  const float y = v_m * inv_texel_size_;
  // Texel centres: level l texel i covers level-0 texels [i*2^l, (i+1)*2^l).
  const float s0 = 1.0f / static_cast<float>(1 << l0);
  const cv::Vec3f a = bilinear(l0, x * s0 - 0.5f, y * s0 - 0.5f);
  if (blend <= 0.01f || l1 == l0) return a;
  const float s1 = 1.0f / static_cast<float>(1 << l1);
  const cv::Vec3f b = bilinear(l1, x * s1 - 0.5f, y * s1 - 0.5f);
  return a + blend * (b - a);
}

}  // namespace lumaslam::synth
