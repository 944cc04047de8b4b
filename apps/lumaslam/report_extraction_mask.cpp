#include "report_extraction_mask.h"

#include <opencv2/imgproc.hpp>

#include "lumaslam/detect/detector_params.h"
#include "lumaslam/detect/dynamic_mask.h"

namespace lumaslam::cli {
namespace {

// As Pipeline::depthInMetres; empty when the frame has no usable depth.
cv::Mat depthInMetres(const cv::Mat& depth, double depth_map_factor) {
  cv::Mat metres;
  if (depth.type() == CV_16UC1) depth.convertTo(metres, CV_32F, 1.0 / depth_map_factor);
  if (depth.type() == CV_32FC1) metres = depth;
  return metres;
}

}  // namespace

cv::Mat previousDynamicMask(const FrameMarks& previous, const io::FrameData& previous_frame,
                            const io::Settings& settings, cv::Size marks_image,
                            cv::Size image_size) {
  if (previous.boxes.empty()) return {};
  const auto params = settings.file
                          ? detect::DetectorParams::fromSettings(*settings.file, false).mask
                          : detect::MaskParams{};
  cv::Mat mask = detect::makeDynamicMask(marks_image, previous.boxes, params.margin_px);
  if (settings.sensor == io::SensorType::Rgbd) {
    cv::Mat depth = depthInMetres(previous_frame.depth, settings.depth.depthMapFactor);
    if (!depth.empty() && depth.size() != marks_image) {
      cv::resize(depth, depth, marks_image, 0.0, 0.0, cv::INTER_NEAREST);
    }
    if (!depth.empty()) mask = detect::refineMaskWithDepth(mask, depth, previous.boxes, params);
  }
  if (mask.size() != image_size) cv::resize(mask, mask, image_size, 0.0, 0.0, cv::INTER_NEAREST);
  return mask;
}

}  // namespace lumaslam::cli
