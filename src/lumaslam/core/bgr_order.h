#pragma once
#include <opencv2/core.hpp>

namespace lumaslam::core {

// The image in OpenCV's channel order (BGR, BGRA), the order every stage works in. `rgb`: the
// caller's colour images are RGB / RGBA (Camera.RGB: 1, e.g. arrays from PIL, imageio or a ROS
// rgb8 topic), so red and blue are swapped into a new image. Other images, and every image
// when `rgb` is false, are returned as they are (shared, not copied).
cv::Mat inBgrOrder(const cv::Mat& image, bool rgb);

}  // namespace lumaslam::core
