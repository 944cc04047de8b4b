#include "report_frame_marks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <opencv2/imgproc.hpp>

namespace lumaslam::cli {
namespace {

const cv::Scalar kGreen(0, 255, 0);
const cv::Scalar kRed(0, 0, 255);

cv::Mat scaledColour(const cv::Mat& image, double scale) {
  cv::Mat scaled = image;
  if (scale < 1.0) cv::resize(image, scaled, cv::Size(), scale, scale, cv::INTER_AREA);
  if (scaled.depth() != CV_8U) scaled.convertTo(scaled, CV_8U);
  if (scaled.channels() == 1) cv::cvtColor(scaled, scaled, cv::COLOR_GRAY2BGR);
  return scaled;
}

cv::Point2f times(const cv::Point2f& p, cv::Point2f scale) {
  return {p.x * scale.x, p.y * scale.y};
}

// The red marks by whole pixel, each as often as the file has it: a keypoint whose rounded
// position has one left is the run's dropped feature there and takes it (the run's mask
// decided on the rounded position too; two keypoints can share a pixel, e.g. on two levels,
// and the motion test may flag one of them only).
using MarkCounts = std::map<std::pair<long, long>, int>;

MarkCounts markCounts(const FrameMarks& marks) {
  MarkCounts counts;
  for (const auto* points : {&marks.dropped, &marks.moving}) {
    for (const cv::Point2f& p : *points) ++counts[{std::lround(p.x), std::lround(p.y)}];
  }
  return counts;
}

bool takeMark(MarkCounts& counts, const cv::Point2f& point) {
  const auto it = counts.find({std::lround(point.x), std::lround(point.y)});
  if (it == counts.end() || it->second == 0) return false;
  --it->second;
  return true;
}

void drawRedMarks(cv::Mat& canvas, const FrameMarks& marks, cv::Point2f scale) {
  for (const cv::Rect2f& box : marks.boxes) {
    const cv::Point2f corner = times(box.tl(), scale);
    const cv::Size2f size(box.width * scale.x, box.height * scale.y);
    cv::rectangle(canvas, cv::Rect2f(corner, size), kRed, 1, cv::LINE_AA);
  }
  for (const cv::Point2f& point : marks.dropped) {
    cv::circle(canvas, times(point, scale), 3, kRed, 2, cv::LINE_AA);
  }
  for (const cv::Point2f& point : marks.moving) {
    cv::drawMarker(canvas, times(point, scale), kRed, cv::MARKER_TILTED_CROSS, 8, 2, cv::LINE_AA);
  }
}

}  // namespace

DrawnFrame drawFrameMarks(const cv::Mat& colour, const std::vector<cv::KeyPoint>& keypoints,
                          const FrameMarks* marks, cv::Size marks_image, int max_width) {
  const double scale = std::min(1.0, static_cast<double>(max_width) / colour.cols);
  DrawnFrame drawn{scaledColour(colour, scale), 0};
  const auto to_canvas = static_cast<float>(scale);
  // The marks' pixels from and to the image's (the same unless Camera.newWidth resized it).
  const cv::Point2f to_marks =
      marks_image.empty() ? cv::Point2f(1.0F, 1.0F)
                          : cv::Point2f(static_cast<float>(marks_image.width) / colour.cols,
                                        static_cast<float>(marks_image.height) / colour.rows);
  MarkCounts counts = marks ? markCounts(*marks) : MarkCounts{};
  for (const cv::KeyPoint& keypoint : keypoints) {
    if (takeMark(counts, times(keypoint.pt, to_marks))) continue;
    cv::circle(drawn.canvas, keypoint.pt * to_canvas, 3, kGreen, 1, cv::LINE_AA);
    ++drawn.green;
  }
  if (marks) {
    drawRedMarks(drawn.canvas, *marks, {to_canvas / to_marks.x, to_canvas / to_marks.y});
  }
  return drawn;
}

}  // namespace lumaslam::cli
