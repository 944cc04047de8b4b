#include "report_frame_marks.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace lumaslam::cli {
namespace {

const cv::Scalar kGreen(0, 255, 0);
const cv::Scalar kRed(0, 0, 255);
constexpr float kSameMarkPx = 2.5F;  // on the drawn image: a keypoint there is a red mark's

cv::Mat scaledColour(const cv::Mat& image, double scale) {
  cv::Mat scaled = image;
  if (scale < 1.0) cv::resize(image, scaled, cv::Size(), scale, scale, cv::INTER_AREA);
  if (scaled.depth() != CV_8U) scaled.convertTo(scaled, CV_8U);
  if (scaled.channels() == 1) cv::cvtColor(scaled, scaled, cv::COLOR_GRAY2BGR);
  return scaled;
}

std::vector<cv::Point2f> scaled(const std::vector<cv::Point2f>& points, cv::Point2f scale) {
  std::vector<cv::Point2f> result;
  result.reserve(points.size());
  for (const cv::Point2f& p : points) result.emplace_back(p.x * scale.x, p.y * scale.y);
  return result;
}

bool nearAny(const cv::Point2f& point, const std::vector<cv::Point2f>& marks) {
  return std::any_of(marks.begin(), marks.end(), [&](const cv::Point2f& mark) {
    return cv::norm(point - mark) <= kSameMarkPx;
  });
}

void drawRedMarks(cv::Mat& canvas, const FrameMarks& marks, cv::Point2f scale) {
  for (const cv::Rect2f& box : marks.boxes) {
    const cv::Point2f corner(box.x * scale.x, box.y * scale.y);
    const cv::Point2f size(box.width * scale.x, box.height * scale.y);
    cv::rectangle(canvas, cv::Rect2f(corner, cv::Size2f(size.x, size.y)), kRed, 1, cv::LINE_AA);
  }
  for (const cv::Point2f& point : scaled(marks.dropped, scale)) {
    cv::circle(canvas, point, 3, kRed, 2, cv::LINE_AA);
  }
  for (const cv::Point2f& point : scaled(marks.moving, scale)) {
    cv::drawMarker(canvas, point, kRed, cv::MARKER_TILTED_CROSS, 8, 2, cv::LINE_AA);
  }
}

}  // namespace

cv::Mat drawFrameMarks(const cv::Mat& colour, const std::vector<cv::KeyPoint>& keypoints,
                       const FrameMarks* marks, cv::Size marks_image, int max_width) {
  const double scale = std::min(1.0, static_cast<double>(max_width) / colour.cols);
  cv::Mat canvas = scaledColour(colour, scale);
  const auto to_canvas = static_cast<float>(scale);
  const cv::Point2f marks_to_canvas =
      marks_image.empty()
          ? cv::Point2f(to_canvas, to_canvas)
          : cv::Point2f(static_cast<float>(canvas.cols) / static_cast<float>(marks_image.width),
                        static_cast<float>(canvas.rows) / static_cast<float>(marks_image.height));
  std::vector<cv::Point2f> red;
  if (marks) {
    red = scaled(marks->dropped, marks_to_canvas);
    const auto moving = scaled(marks->moving, marks_to_canvas);
    red.insert(red.end(), moving.begin(), moving.end());
  }
  for (const cv::KeyPoint& keypoint : keypoints) {
    const cv::Point2f point = keypoint.pt * to_canvas;
    if (!nearAny(point, red)) cv::circle(canvas, point, 3, kGreen, 1, cv::LINE_AA);
  }
  if (marks) drawRedMarks(canvas, *marks, marks_to_canvas);
  return canvas;
}

}  // namespace lumaslam::cli
