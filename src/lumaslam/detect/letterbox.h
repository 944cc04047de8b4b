#pragma once
// YOLOv5's letterbox: resize keeping the aspect ratio, pad to a square with gray 114.
#include <opencv2/core.hpp>

namespace lumaslam::detect {

// Maps boxes from network-input pixels back to the original image.
struct LetterboxTransform {
  double scale = 1.0;  // input pixels per image pixel
  int pad_left = 0;
  int pad_top = 0;
  cv::Size image_size;

  // A centre/size box in input pixels -> image pixels, clipped to the image.
  cv::Rect2f toImage(float cx, float cy, float w, float h) const;
};

struct Letterboxed {
  cv::Mat image;  // size x size, same type as the input
  LetterboxTransform transform;
};

// Throws Error for an empty image or a size < 1.
Letterboxed letterbox(const cv::Mat& image, int size);

}  // namespace lumaslam::detect
