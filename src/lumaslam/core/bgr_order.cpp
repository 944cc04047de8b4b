#include "lumaslam/core/bgr_order.h"

#include <opencv2/imgproc.hpp>

namespace lumaslam::core {

cv::Mat inBgrOrder(const cv::Mat& image, bool rgb) {
  // Other channel counts are left to the pipeline's own input check.
  if (!rgb || image.empty() || (image.channels() != 3 && image.channels() != 4)) return image;
  cv::Mat bgr;
  cv::cvtColor(image, bgr, image.channels() == 4 ? cv::COLOR_RGBA2BGRA : cv::COLOR_RGB2BGR);
  return bgr;
}

}  // namespace lumaslam::core
