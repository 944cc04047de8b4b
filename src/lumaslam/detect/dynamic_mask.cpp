#include "lumaslam/detect/dynamic_mask.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::detect {
namespace {

cv::Rect grown(const cv::Rect2f& box, int margin_px, const cv::Size& size) {
  const cv::Rect2f outer(box.x - margin_px, box.y - margin_px, box.width + 2.0f * margin_px,
                         box.height + 2.0f * margin_px);
  // Round outwards so a box's every pixel is covered.
  const cv::Point top_left(static_cast<int>(std::floor(outer.x)),
                           static_cast<int>(std::floor(outer.y)));
  const cv::Point bottom_right(static_cast<int>(std::ceil(outer.x + outer.width)),
                               static_cast<int>(std::ceil(outer.y + outer.height)));
  return cv::Rect(top_left, bottom_right) & cv::Rect(cv::Point(), size);
}

}  // namespace

cv::Mat makeDynamicMask(const cv::Size& image_size, const std::vector<cv::Rect2f>& boxes,
                        int margin_px) {
  if (image_size.width <= 0 || image_size.height <= 0) {
    fail("makeDynamicMask: invalid image size {}x{}", image_size.width, image_size.height);
  }
  if (margin_px < 0) fail("makeDynamicMask: margin must be >= 0, found {}", margin_px);
  cv::Mat mask = cv::Mat::zeros(image_size, CV_8U);
  for (const auto& box : boxes) {
    if (box.width <= 0 || box.height <= 0) continue;
    mask(grown(box, margin_px, image_size)).setTo(255);
  }
  return mask;
}

std::optional<double> personDepth(const cv::Mat& depth_m, const cv::Rect2f& box,
                                  const MaskParams& params) {
  if (depth_m.type() != CV_32F)
    fail("personDepth: depth must be CV_32F metres, found type {}", depth_m.type());
  const float fraction = params.depth_inner_fraction;
  const cv::Rect2f inner(box.x + box.width * (1 - fraction) / 2,
                         box.y + box.height * (1 - fraction) / 2, box.width * fraction,
                         box.height * fraction);
  const cv::Rect region = cv::Rect(inner) & cv::Rect(cv::Point(), depth_m.size());
  if (region.empty()) return std::nullopt;
  std::vector<float> valid;
  valid.reserve(static_cast<std::size_t>(region.area()));
  for (int y = region.y; y < region.br().y; ++y) {
    const float* row = depth_m.ptr<float>(y);
    for (int x = region.x; x < region.br().x; ++x) {
      if (std::isfinite(row[x]) && row[x] > 0.0f) valid.push_back(row[x]);
    }
  }
  if (valid.empty()) return std::nullopt;
  const auto rank =
      static_cast<std::ptrdiff_t>(params.depth_percentile * static_cast<double>(valid.size() - 1));
  std::nth_element(valid.begin(), valid.begin() + rank, valid.end());
  return valid[static_cast<std::size_t>(rank)];
}

cv::Mat refineMaskWithDepth(const cv::Mat& mask, const cv::Mat& depth_m,
                            const std::vector<cv::Rect2f>& boxes, const MaskParams& params) {
  if (mask.type() != CV_8U)
    fail("refineMaskWithDepth: mask must be CV_8U, found type {}", mask.type());
  if (depth_m.type() != CV_32F)
    fail("refineMaskWithDepth: depth must be CV_32F metres, found type {}", depth_m.type());
  if (mask.size() != depth_m.size()) {
    fail("refineMaskWithDepth: mask {}x{} and depth {}x{} differ in size", mask.cols, mask.rows,
         depth_m.cols, depth_m.rows);
  }
  // keep: pixels some box says belong to (or may belong to) its person.
  cv::Mat covered = cv::Mat::zeros(mask.size(), CV_8U);
  cv::Mat keep = cv::Mat::zeros(mask.size(), CV_8U);
  const cv::Mat invalid = ~(depth_m > 0.0f);  // comparisons with NaN are false: NaN is invalid
  for (const auto& box : boxes) {
    const cv::Rect region = grown(box, params.margin_px, mask.size());
    if (region.empty()) continue;
    covered(region).setTo(255);
    const auto person = personDepth(depth_m, box, params);
    if (!person) {
      keep(region).setTo(255);
      continue;
    }
    const cv::Mat near = depth_m(region) <= static_cast<float>(*person + params.depth_tolerance_m);
    keep(region) |= near | invalid(region);
  }
  // A feature's descriptor reads a patch around it: a background pixel right next to the
  // person's silhouette describes the person and moves with them, so only pixels at least
  // depth_edge_px away from every kept pixel are freed.
  if (params.depth_edge_px > 0) {
    const int size = 2 * params.depth_edge_px + 1;
    cv::dilate(keep, keep, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(size, size)));
  }
  cv::Mat refined = mask.clone();
  refined.setTo(0, covered & ~keep);
  return refined;
}

std::vector<int> filterKeypoints(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& mask) {
  if (mask.type() != CV_8U) fail("filterKeypoints: mask must be CV_8U, found type {}", mask.type());
  std::vector<int> kept;
  kept.reserve(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const int x = static_cast<int>(std::lround(keypoints[i].pt.x));
    const int y = static_cast<int>(std::lround(keypoints[i].pt.y));
    const bool inside = x >= 0 && y >= 0 && x < mask.cols && y < mask.rows;
    if (!inside || mask.at<uchar>(y, x) == 0) kept.push_back(static_cast<int>(i));
  }
  return kept;
}

}  // namespace lumaslam::detect
