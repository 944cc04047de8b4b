#include "lumaslam/feature/steered_brief.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "lumaslam/feature/brief_pattern.h"

namespace lumaslam::feature {

void computeSteeredBrief(const cv::Mat& smoothed, cv::Point2f point, float angleDegrees,
                         std::uint8_t* descriptor) {
  const float radians = angleDegrees * static_cast<float>(CV_PI / 180.0);
  const float c = std::cos(radians);
  const float s = std::sin(radians);
  const int step = static_cast<int>(smoothed.step);
  const uchar* center = smoothed.ptr<uchar>(cvRound(point.y)) + cvRound(point.x);
  // Pattern offset (x, y) rotated by the angle: (x c - y s, x s + y c), rounded to a pixel.
  const auto sample = [&](int x, int y) {
    return center[cvRound(x * s + y * c) * step + cvRound(x * c - y * s)];
  };
  const auto& pattern = briefPattern();
  for (int byte = 0; byte < kDescriptorBytes; ++byte) {
    std::uint8_t value = 0;
    for (int bit = 0; bit < 8; ++bit) {
      const BriefPair& pair = pattern[byte * 8 + bit];
      if (sample(pair.x1, pair.y1) < sample(pair.x2, pair.y2)) value |= 1u << bit;
    }
    descriptor[byte] = value;
  }
}

cv::Mat smoothForDescriptors(const cv::Mat& image) {
  cv::Mat smoothed;
  cv::GaussianBlur(image, smoothed, cv::Size(7, 7), 2.0, 2.0, cv::BORDER_REFLECT_101);
  return smoothed;
}

}  // namespace lumaslam::feature
