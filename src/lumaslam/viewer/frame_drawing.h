#pragma once
// The two frame pictures of the viewer, drawn on its own thread: the raw image and the image
// features were taken from, each with the kept (green) and dropped (red) keypoints, the
// detection boxes (yellow) and the dynamic mask (red tint).
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/viewer/frame_view.h"

namespace lumaslam::viewer {

enum class FramePicture { Raw, Enhanced };

// BGR, at most max_width pixels wide (scaled down with the overlays).
cv::Mat drawFramePicture(const FrameView& view, FramePicture picture, int max_width = 640);

std::vector<unsigned char> encodeJpeg(const cv::Mat& bgr, int quality = 80);

}  // namespace lumaslam::viewer
