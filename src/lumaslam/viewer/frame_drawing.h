#pragma once
// The frame pictures of the viewer, drawn on its own thread: the raw image and the image
// features were taken from, each with the kept (green) and dropped (red) keypoints, the
// detection boxes (yellow) and the dynamic mask (red tint); and a stereo run's right image as
// read, without marks (they are the left image's).
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/viewer/frame_view.h"

namespace lumaslam::viewer {

enum class FramePicture { Raw, Enhanced, Right };

// BGR, at most max_width pixels wide (scaled down with the overlays); empty when the view has
// no such image (Right of a run that is not stereo).
cv::Mat drawFramePicture(const FrameView& view, FramePicture picture, int max_width = 640);

std::vector<unsigned char> encodeJpeg(const cv::Mat& bgr, int quality = 80);

}  // namespace lumaslam::viewer
