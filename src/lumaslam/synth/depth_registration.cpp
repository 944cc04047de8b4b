#include "lumaslam/synth/depth_registration.h"

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::synth {

namespace {

cv::Mat resampleNearest(const cv::Mat& map, const cv::Mat& dst_to_src) {
  if (map.empty()) return map;
  cv::Mat out;
  cv::warpAffine(map, out, dst_to_src, map.size(), cv::INTER_NEAREST | cv::WARP_INVERSE_MAP,
                 cv::BORDER_CONSTANT, cv::Scalar(0.0));
  return out;
}

}  // namespace

DepthSensorInput misregister(const DepthSensorInput& input, cv::Point2f shift_px, float scale) {
  if (!(scale > 0.5f && scale < 2.0f))
    fail("depth misregistration: scale {} is not a small scale error", scale);
  if (shift_px == cv::Point2f(0.0f, 0.0f) && scale == 1.0f) return input;
  // Depth pixel p shows the registered depth at c + (p - c - shift) / scale.
  const double cx = (input.depth_m.cols - 1) * 0.5, cy = (input.depth_m.rows - 1) * 0.5;
  const double inv = 1.0 / scale;
  const cv::Mat dst_to_src = (cv::Mat_<double>(2, 3) << inv, 0.0, cx - (cx + shift_px.x) * inv, 0.0,
                              inv, cy - (cy + shift_px.y) * inv);
  return {resampleNearest(input.depth_m, dst_to_src), resampleNearest(input.ir_albedo, dst_to_src),
          resampleNearest(input.incidence_cos, dst_to_src)};
}

}  // namespace lumaslam::synth
