#include "lumaslam/viewer/frame_drawing.h"

#include <algorithm>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace lumaslam::viewer {
namespace {

cv::Mat toBgr(const cv::Mat& image) {
  cv::Mat bgr;
  if (image.channels() == 1) {
    cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  } else {
    bgr = image.clone();
  }
  if (bgr.depth() != CV_8U) bgr.convertTo(bgr, CV_8U);
  return bgr;
}

void tintMask(cv::Mat& bgr, const cv::Mat& mask) {
  if (mask.empty() || mask.size() != bgr.size()) return;
  cv::Mat red(bgr.size(), bgr.type(), cv::Scalar(0, 0, 255));
  cv::Mat tinted;
  cv::addWeighted(bgr, 0.6, red, 0.4, 0.0, tinted);
  tinted.copyTo(bgr, mask);
}

void drawPoints(cv::Mat& bgr, const std::vector<cv::Point2f>& points, const cv::Scalar& colour,
                double scale) {
  for (const auto& point : points) {
    cv::circle(bgr, point * scale, 2, colour, 1, cv::LINE_AA);
  }
}

void drawOverlays(cv::Mat& bgr, const FrameView& view, double scale) {
  for (const auto& box : view.boxes) {
    const cv::Rect2f scaled(box.x * scale, box.y * scale, box.width * scale, box.height * scale);
    cv::rectangle(bgr, scaled, cv::Scalar(0, 220, 255), 2);
  }
  drawPoints(bgr, view.kept, cv::Scalar(60, 220, 60), scale);
  drawPoints(bgr, view.dropped, cv::Scalar(40, 40, 255), scale);
}

cv::Mat scaledRight(const cv::Mat& right, int max_width) {
  if (right.empty()) return {};
  cv::Mat bgr = toBgr(right);
  const double scale = std::min(1.0, static_cast<double>(max_width) / bgr.cols);
  if (scale < 1.0) cv::resize(bgr, bgr, cv::Size(), scale, scale, cv::INTER_AREA);
  return bgr;
}

}  // namespace

cv::Mat drawFramePicture(const FrameView& view, FramePicture picture, int max_width) {
  if (picture == FramePicture::Right) return scaledRight(view.right, max_width);
  const bool raw = picture == FramePicture::Raw || view.features_image.empty();
  const cv::Mat& source = raw ? view.raw : view.features_image;
  if (source.empty()) return {};
  cv::Mat bgr = toBgr(source);
  const bool overlays = !raw || view.overlays_fit_raw;
  if (overlays) tintMask(bgr, view.dynamic_mask);
  const double scale = std::min(1.0, static_cast<double>(max_width) / bgr.cols);
  if (scale < 1.0) cv::resize(bgr, bgr, cv::Size(), scale, scale, cv::INTER_AREA);
  if (overlays) drawOverlays(bgr, view, scale);
  return bgr;
}

std::vector<unsigned char> encodeJpeg(const cv::Mat& bgr, int quality) {
  std::vector<unsigned char> bytes;
  if (!bgr.empty()) cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, quality});
  return bytes;
}

}  // namespace lumaslam::viewer
