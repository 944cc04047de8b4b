#include "lumaslam/detect/letterbox.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::detect {

cv::Rect2f LetterboxTransform::toImage(float cx, float cy, float w, float h) const {
  const auto unpad_x = [&](float x) { return static_cast<float>((x - pad_left) / scale); };
  const auto unpad_y = [&](float y) { return static_cast<float>((y - pad_top) / scale); };
  const float width = static_cast<float>(image_size.width);
  const float height = static_cast<float>(image_size.height);
  const float x1 = std::clamp(unpad_x(cx - w / 2), 0.0f, width);
  const float y1 = std::clamp(unpad_y(cy - h / 2), 0.0f, height);
  const float x2 = std::clamp(unpad_x(cx + w / 2), 0.0f, width);
  const float y2 = std::clamp(unpad_y(cy + h / 2), 0.0f, height);
  return {x1, y1, x2 - x1, y2 - y1};
}

Letterboxed letterbox(const cv::Mat& image, int size) {
  if (image.empty()) fail("letterbox: empty image");
  if (size < 1) fail("letterbox: input size must be >= 1, found {}", size);
  LetterboxTransform transform;
  transform.image_size = image.size();
  transform.scale =
      std::min(static_cast<double>(size) / image.cols, static_cast<double>(size) / image.rows);
  const cv::Size resized_size(
      std::clamp(static_cast<int>(std::lround(image.cols * transform.scale)), 1, size),
      std::clamp(static_cast<int>(std::lround(image.rows * transform.scale)), 1, size));
  // Centred padding, rounded as YOLOv5's letterbox does.
  const double pad_x = (size - resized_size.width) / 2.0;
  const double pad_y = (size - resized_size.height) / 2.0;
  transform.pad_left = static_cast<int>(std::lround(pad_x - 0.1));
  transform.pad_top = static_cast<int>(std::lround(pad_y - 0.1));
  const int pad_right = size - resized_size.width - transform.pad_left;
  const int pad_bottom = size - resized_size.height - transform.pad_top;

  cv::Mat resized;
  if (resized_size == image.size()) {
    resized = image;
  } else {
    cv::resize(image, resized, resized_size, 0, 0, cv::INTER_LINEAR);
  }
  Letterboxed out;
  out.transform = transform;
  cv::copyMakeBorder(resized, out.image, transform.pad_top, pad_bottom, transform.pad_left,
                     pad_right, cv::BORDER_CONSTANT, cv::Scalar::all(114));
  return out;
}

}  // namespace lumaslam::detect
