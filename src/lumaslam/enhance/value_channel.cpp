#include "lumaslam/enhance/value_channel.h"

#include <array>

namespace lumaslam::enhance {

cv::Mat valueChannel(const cv::Mat& bgr) {
  CV_Assert(bgr.type() == CV_8UC3);
  std::array<cv::Mat, 3> planes;
  cv::split(bgr, planes.data());
  cv::Mat value;
  cv::max(planes[0], planes[1], value);
  cv::max(value, planes[2], value);
  return value;
}

cv::Mat rebuildColour(const cv::Mat& bgr, const cv::Mat& channel_old, const cv::Mat& channel_new) {
  CV_Assert(bgr.type() == CV_8UC3 && channel_old.type() == CV_8UC1 &&
            channel_new.type() == CV_8UC1 && bgr.size() == channel_old.size() &&
            bgr.size() == channel_new.size());
  static const std::array<float, 256> inverse = [] {
    std::array<float, 256> table{};
    for (int v = 1; v < 256; ++v) table[v] = 1.0f / static_cast<float>(v);
    return table;
  }();
  cv::Mat out(bgr.size(), CV_8UC3);
  for (int y = 0; y < bgr.rows; ++y) {
    const uchar* in = bgr.ptr<uchar>(y);
    const uchar* old_row = channel_old.ptr<uchar>(y);
    const uchar* new_row = channel_new.ptr<uchar>(y);
    uchar* dst = out.ptr<uchar>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      if (old_row[x] == 0) {
        dst[3 * x] = dst[3 * x + 1] = dst[3 * x + 2] = new_row[x];
        continue;
      }
      const float scale = static_cast<float>(new_row[x]) * inverse[old_row[x]];
      for (int c = 0; c < 3; ++c) {
        dst[3 * x + c] = cv::saturate_cast<uchar>(static_cast<float>(in[3 * x + c]) * scale);
      }
    }
  }
  return out;
}

}  // namespace lumaslam::enhance
