#include "lumaslam/enhance/value_channel.h"

#include <opencv2/core/hal/intrin.hpp>

namespace lumaslam::enhance {
namespace {

// The scalar rebuild of one pixel; the SIMD loop below computes exactly the same float
// expression (IEEE division, round half to even), so the two are bit-identical.
inline void rebuildPixel(const uchar* in, int old_value, int new_value, uchar* dst) {
  if (old_value == 0) {
    dst[0] = dst[1] = dst[2] = static_cast<uchar>(new_value);
    return;
  }
  const float scale = static_cast<float>(new_value) * (1.0f / static_cast<float>(old_value));
  for (int c = 0; c < 3; ++c) {
    dst[c] = cv::saturate_cast<uchar>(static_cast<float>(in[c]) * scale);
  }
}

#if CV_SIMD
// 4 float lanes-worth of one 8-bit channel (quarter q of a v_uint8).
inline void toFloat(const cv::v_uint8& v, cv::v_float32 (&out)[4]) {
  cv::v_uint16 lo;
  cv::v_uint16 hi;
  cv::v_expand(v, lo, hi);
  cv::v_uint32 a;
  cv::v_uint32 b;
  cv::v_expand(lo, a, b);
  out[0] = cv::v_cvt_f32(cv::v_reinterpret_as_s32(a));
  out[1] = cv::v_cvt_f32(cv::v_reinterpret_as_s32(b));
  cv::v_expand(hi, a, b);
  out[2] = cv::v_cvt_f32(cv::v_reinterpret_as_s32(a));
  out[3] = cv::v_cvt_f32(cv::v_reinterpret_as_s32(b));
}

inline cv::v_uint8 roundAndPack(const cv::v_float32 (&in)[4]) {
  const cv::v_int16 lo = cv::v_pack(cv::v_round(in[0]), cv::v_round(in[1]));
  const cv::v_int16 hi = cv::v_pack(cv::v_round(in[2]), cv::v_round(in[3]));
  return cv::v_pack_u(lo, hi);
}
#endif

}  // namespace

void valueChannel(const cv::Mat& bgr, cv::Mat& value) {
  CV_Assert(bgr.type() == CV_8UC3);
  value.create(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y) {
    const uchar* in = bgr.ptr<uchar>(y);
    uchar* out = value.ptr<uchar>(y);
    int x = 0;
#if CV_SIMD
    for (; x + cv::v_uint8::nlanes <= bgr.cols; x += cv::v_uint8::nlanes) {
      cv::v_uint8 b;
      cv::v_uint8 g;
      cv::v_uint8 r;
      cv::v_load_deinterleave(in + 3 * x, b, g, r);
      cv::v_store(out + x, cv::v_max(cv::v_max(b, g), r));
    }
#endif
    for (; x < bgr.cols; ++x) out[x] = std::max({in[3 * x], in[3 * x + 1], in[3 * x + 2]});
  }
}

cv::Mat valueChannel(const cv::Mat& bgr) {
  cv::Mat value;
  valueChannel(bgr, value);
  return value;
}

void rebuildColour(const cv::Mat& bgr, const cv::Mat& channel_old, const cv::Mat& channel_new,
                   cv::Mat& out) {
  CV_Assert(bgr.type() == CV_8UC3 && channel_old.type() == CV_8UC1 &&
            channel_new.type() == CV_8UC1 && bgr.size() == channel_old.size() &&
            bgr.size() == channel_new.size());
  out.create(bgr.size(), CV_8UC3);
  for (int y = 0; y < bgr.rows; ++y) {
    const uchar* in = bgr.ptr<uchar>(y);
    const uchar* old_row = channel_old.ptr<uchar>(y);
    const uchar* new_row = channel_new.ptr<uchar>(y);
    uchar* dst = out.ptr<uchar>(y);
    int x = 0;
#if CV_SIMD
    const cv::v_float32 one = cv::vx_setall_f32(1.0f);
    for (; x + cv::v_uint8::nlanes <= bgr.cols; x += cv::v_uint8::nlanes) {
      const cv::v_uint8 old_v = cv::vx_load(old_row + x);
      const cv::v_uint8 new_v = cv::vx_load(new_row + x);
      cv::v_float32 old_f[4];
      cv::v_float32 scale[4];
      toFloat(old_v, old_f);
      toFloat(new_v, scale);
      for (int q = 0; q < 4; ++q) scale[q] = scale[q] * (one / old_f[q]);
      cv::v_uint8 channels[3];
      cv::v_load_deinterleave(in + 3 * x, channels[0], channels[1], channels[2]);
      // Where old is 0 the pixel becomes gray at the new value (scale is inf or NaN there).
      const cv::v_uint8 black = old_v == cv::vx_setzero_u8();
      for (auto& channel : channels) {
        cv::v_float32 f[4];
        toFloat(channel, f);
        for (int q = 0; q < 4; ++q) f[q] = f[q] * scale[q];
        channel = cv::v_select(black, new_v, roundAndPack(f));
      }
      cv::v_store_interleave(dst + 3 * x, channels[0], channels[1], channels[2]);
    }
#endif
    for (; x < bgr.cols; ++x) rebuildPixel(in + 3 * x, old_row[x], new_row[x], dst + 3 * x);
  }
}

cv::Mat rebuildColour(const cv::Mat& bgr, const cv::Mat& channel_old, const cv::Mat& channel_new) {
  cv::Mat out;
  rebuildColour(bgr, channel_old, channel_new, out);
  return out;
}

}  // namespace lumaslam::enhance
