#include "lumaslam/synth/texture.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/spare_row.h"

namespace lumaslam::synth {

namespace {

// BGR texel as floats in lanes 0-2 (lane 3 is the next texel's blue, unused).
inline cv::v_float32x4 texel(const std::uint8_t* p) {
  // v_load_expand_q reads its 4 bytes as one int; texels are 3 bytes apart, so copy them to
  // an aligned word first (a misaligned int load is undefined; the copy compiles to one load).
  alignas(4) std::uint8_t word[4];
  std::memcpy(word, p, sizeof(word));
  return cv::v_cvt_f32(cv::v_reinterpret_as_s32(cv::v_load_expand_q(word)));
}

// Bilinear lookup in texels of one level, 0..255 per channel.
inline cv::v_float32x4 bilinear(const cv::Mat& img, float x, float y) {
  x = std::clamp(x, 0.0f, static_cast<float>(img.cols - 1));
  y = std::clamp(y, 0.0f, static_cast<float>(img.rows - 1));
  const int x0 = std::min(static_cast<int>(x), img.cols - 2 < 0 ? 0 : img.cols - 2);
  const int y0 = std::min(static_cast<int>(y), img.rows - 2 < 0 ? 0 : img.rows - 2);
  const int x1 = std::min(x0 + 1, img.cols - 1);
  const int y1 = std::min(y0 + 1, img.rows - 1);
  const cv::v_float32x4 fx = cv::v_setall_f32(x - static_cast<float>(x0));
  const cv::v_float32x4 fy = cv::v_setall_f32(y - static_cast<float>(y0));
  const std::uint8_t* row0 = img.ptr<std::uint8_t>(y0);
  const std::uint8_t* row1 = img.ptr<std::uint8_t>(y1);
  const cv::v_float32x4 a = texel(row0 + 3 * x0), b = texel(row0 + 3 * x1);
  const cv::v_float32x4 c = texel(row1 + 3 * x0), d = texel(row1 + 3 * x1);
  const cv::v_float32x4 top = a + fx * (b - a);
  const cv::v_float32x4 bottom = c + fx * (d - c);
  return top + fy * (bottom - top);
}

}  // namespace

MipTexture::MipTexture(const cv::Mat& image, float texel_size_m)
    : texel_size_(texel_size_m), inv_texel_size_(1.0f / texel_size_m) {
  if (image.empty() || image.type() != CV_8UC3)
    fail("MipTexture: expected a non-empty CV_8UC3 image");
  if (!(texel_size_m > 0.0f)) fail("MipTexture: texel size must be positive, got {}", texel_size_m);
  levels_.push_back(withSpareRow(image));
  while (levels_.back().cols > 4 && levels_.back().rows > 4) {
    cv::Mat next;
    cv::pyrDown(levels_.back(), next);
    levels_.push_back(withSpareRow(next));
  }
}

cv::Vec3f MipTexture::sample(float u_m, float v_m, float footprint_m) const {
  const float footprint_texels = footprint_m * inv_texel_size_;
  // log2 from the float's exponent + linear mantissa (error < 0.09 levels; plenty for a level
  // of detail): for (1 + f) * 2^e it is e + f.
  float lod = 0.0f;
  if (footprint_texels > 1.0f) {
    const auto bits = std::bit_cast<std::uint32_t>(footprint_texels);
    lod = static_cast<float>(static_cast<int>(bits >> 23) - 127) +
          static_cast<float>(bits & 0x7fffffu) * (1.0f / 8388608.0f);
  }
  const int max_level = levelCount() - 1;
  const int l0 = std::min(static_cast<int>(lod), max_level);
  const int l1 = std::min(l0 + 1, max_level);
  // "Brilinear": one level for the first half of each octave, a blend over the second half.
  const float blend = std::clamp(2.0f * (lod - static_cast<float>(l0)) - 1.0f, 0.0f, 1.0f);
  const float x = u_m * inv_texel_size_;
  const float y = v_m * inv_texel_size_;
  // Texel centres: level l texel i covers level-0 texels [i*2^l, (i+1)*2^l).
  const cv::v_float32x4 to_unit = cv::v_setall_f32(1.0f / 255.0f);
  const float s0 = 1.0f / static_cast<float>(1 << l0);
  cv::v_float32x4 out =
      bilinear(levels_[static_cast<size_t>(l0)], x * s0 - 0.5f, y * s0 - 0.5f) * to_unit;
  if (blend > 0.01f && l1 != l0) {
    const float s1 = 1.0f / static_cast<float>(1 << l1);
    const cv::v_float32x4 b =
        bilinear(levels_[static_cast<size_t>(l1)], x * s1 - 0.5f, y * s1 - 0.5f) * to_unit;
    out = out + cv::v_setall_f32(blend) * (b - out);
  }
  float lanes[4];
  cv::v_store(lanes, out);
  return {lanes[0], lanes[1], lanes[2]};
}

}  // namespace lumaslam::synth
