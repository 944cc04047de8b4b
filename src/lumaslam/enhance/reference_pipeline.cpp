#include "lumaslam/enhance/reference_pipeline.h"

#include <opencv2/imgproc.hpp>

#include "lumaslam/enhance/brightness_compensation.h"
#include "lumaslam/enhance/clahe.h"
#include "lumaslam/enhance/quality_gate.h"

namespace lumaslam::enhance {
namespace {

cv::Mat valueOf(const cv::Mat& bgr) {
  cv::Mat planes[3];
  cv::split(bgr, planes);
  cv::Mat value;
  cv::max(planes[0], planes[1], value);
  cv::max(value, planes[2], value);
  return value;
}

cv::Mat rebuild(const cv::Mat& bgr, const cv::Mat& channel_old, const cv::Mat& channel_new) {
  cv::Mat out(bgr.size(), CV_8UC3);
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const int old_value = channel_old.at<uchar>(y, x);
      const int new_value = channel_new.at<uchar>(y, x);
      const auto& in = bgr.at<cv::Vec3b>(y, x);
      auto& dst = out.at<cv::Vec3b>(y, x);
      if (old_value == 0) {
        dst = cv::Vec3b::all(static_cast<uchar>(new_value));
        continue;
      }
      const float scale = static_cast<float>(new_value) / static_cast<float>(old_value);
      for (int c = 0; c < 3; ++c) dst[c] = cv::saturate_cast<uchar>(in[c] * scale);
    }
  }
  return out;
}

}  // namespace

ReferenceEnhancer::ReferenceEnhancer(EnhancerParams params)
    : params_(std::move(params)), limit_model_(params_.clahe) {}

EnhancedFrame ReferenceEnhancer::enhance(const cv::Mat& image) {
  CV_Assert(image.type() == CV_8UC1 || image.type() == CV_8UC3);
  EnhancedFrame frame;
  cv::Mat channel = image;
  if (image.channels() == 3) {
    if (params_.channel == WorkChannel::kValue) {
      channel = valueOf(image);
    } else {
      cv::cvtColor(image, channel, cv::COLOR_BGR2GRAY);
    }
  }
  // Eq. 1-4
  FrameReport& report = frame.report;
  report.brightness = measureBrightness(channel);
  report.compensated = params_.compensation.enabled &&
                       QualityGate(params_.gate).needsCompensation(report.brightness);
  cv::Mat adjusted = channel;
  if (report.compensated) {
    adjusted = BrightnessCompensation(params_.compensation).apply(channel, report.brightness.mean);
  }
  // Eq. 9-19
  cv::Mat enhanced = adjusted;
  const auto& c = params_.clahe;
  if (c.enabled) {
    const Clahe clahe(c.tiles_x, c.tiles_y);
    cv::Mat limits(c.tiles_y, c.tiles_x, CV_64FC1, cv::Scalar(c.fixed_limit));
    if (c.limit_mode == ClipLimitMode::kGlobal) {
      const ContrastStats stats = ContrastImages(adjusted, c.sigma).stats();
      limit_model_.observe(stats);
      report.contrast = stats;
      limits.setTo(limit_model_.limit(stats));
    } else if (c.limit_mode == ClipLimitMode::kLocal) {
      const Clahe::Tiling tiling = clahe.tiling(adjusted);
      const ContrastImages images(tiling.padded, c.sigma);
      for (int ty = 0; ty < c.tiles_y; ++ty) {
        for (int tx = 0; tx < c.tiles_x; ++tx) {
          const ContrastStats stats = images.stats({tx * tiling.tile.width, ty * tiling.tile.height,
                                                    tiling.tile.width, tiling.tile.height});
          limit_model_.observe(stats);
          limits.at<double>(ty, tx) = limit_model_.limit(stats);
        }
      }
    }
    report.limit = cv::mean(limits)[0];
    enhanced = clahe.apply(adjusted, limits);
  }
  // Eq. 5-8
  if (image.channels() == 1) {
    frame.colour = frame.gray = enhanced;
    return frame;
  }
  frame.colour = rebuild(image, channel, enhanced);
  if (params_.channel == WorkChannel::kGray) {
    frame.gray = enhanced;
  } else {
    cv::cvtColor(frame.colour, frame.gray, cv::COLOR_BGR2GRAY);
  }
  return frame;
}

}  // namespace lumaslam::enhance
