#include "lumaslam/enhance/enhancer.h"

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/enhance/value_channel.h"

namespace lumaslam::enhance {
namespace {

// 8-bit gray or BGR; BGRA loses its alpha. Everything else is an Error.
cv::Mat normaliseInput(const cv::Mat& image) {
  if (image.empty()) fail("enhance: empty image");
  if (image.depth() != CV_8U) {
    fail("enhance: expected an 8-bit image, got {} (convert it first)",
         cv::typeToString(image.type()));
  }
  switch (image.channels()) {
    case 1:
    case 3:
      return image;
    case 4: {
      cv::Mat bgr;
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      return bgr;
    }
    default:
      fail("enhance: expected 1, 3 or 4 channels, got {}", image.channels());
  }
}

}  // namespace

Enhancer::Enhancer(EnhancerParams params)
    : params_(std::move(params)),
      gate_(params_.gate),
      compensation_(params_.compensation),
      clahe_(params_.clahe.tiles_x, params_.clahe.tiles_y),
      limit_model_(params_.clahe) {}

Enhancer::Prepared Enhancer::prepare(const cv::Mat& image) const {
  Prepared p;
  const cv::Mat input = normaliseInput(image);
  if (input.channels() == 1) {
    p.channel = input;  // gray is its own V
  } else {
    p.bgr = input;
    if (params_.channel == WorkChannel::kValue) {
      p.channel = valueChannel(input);
    } else {
      cv::cvtColor(input, p.channel, cv::COLOR_BGR2GRAY);
    }
  }
  p.report.brightness = measureBrightness(p.channel);
  p.report.compensated =
      params_.compensation.enabled && gate_.needsCompensation(p.report.brightness);
  p.adjusted =
      p.report.compensated ? compensation_.apply(p.channel, p.report.brightness.mean) : p.channel;
  return p;
}

cv::Mat Enhancer::equalise(const cv::Mat& channel, FrameReport& report) {
  const auto& c = params_.clahe;
  if (!c.enabled) return channel;
  if (c.limit_mode == ClipLimitMode::kFixed) {
    report.limit = c.fixed_limit;
    return clahe_.apply(channel, c.fixed_limit);
  }
  if (c.limit_mode == ClipLimitMode::kGlobal) {
    const ContrastStats stats = measureContrast(channel, c.sigma);
    limit_model_.observe(stats);
    report.contrast = stats;
    report.limit = limit_model_.limit(stats);
    return clahe_.apply(channel, *report.limit);
  }
  // Local: Eq. 11 per tile, from the tile's own statistics.
  const Clahe::Tiling tiling = clahe_.tiling(channel);
  const ContrastImages images(tiling.padded, c.sigma);
  cv::Mat limits(c.tiles_y, c.tiles_x, CV_64FC1);
  ContrastStats mean_stats;
  for (int ty = 0; ty < c.tiles_y; ++ty) {
    for (int tx = 0; tx < c.tiles_x; ++tx) {
      const cv::Rect rect(tx * tiling.tile.width, ty * tiling.tile.height, tiling.tile.width,
                          tiling.tile.height);
      const ContrastStats stats = images.stats(rect);
      limit_model_.observe(stats);
      limits.at<double>(ty, tx) = limit_model_.limit(stats);
      mean_stats.sigma += stats.sigma / limits.total();
      mean_stats.d += stats.d / limits.total();
    }
  }
  report.contrast = mean_stats;
  report.limit = cv::mean(limits)[0];
  return clahe_.apply(channel, limits);
}

EnhancedFrame Enhancer::enhance(const cv::Mat& image) {
  Prepared p = prepare(image);
  EnhancedFrame frame;
  frame.report = p.report;
  const cv::Mat enhanced = equalise(p.adjusted, frame.report);
  if (p.bgr.empty()) {
    frame.colour = enhanced;
    frame.gray = enhanced;
    return frame;
  }
  frame.colour = rebuildColour(p.bgr, p.channel, enhanced);
  if (params_.channel == WorkChannel::kGray) {
    frame.gray = enhanced;
  } else {
    cv::cvtColor(frame.colour, frame.gray, cv::COLOR_BGR2GRAY);
  }
  return frame;
}

std::vector<ContrastStats> Enhancer::contrastOf(const cv::Mat& image) const {
  const Prepared p = prepare(image);
  const auto& c = params_.clahe;
  if (c.limit_mode != ClipLimitMode::kLocal) return {measureContrast(p.adjusted, c.sigma)};
  const Clahe::Tiling tiling = clahe_.tiling(p.adjusted);
  const ContrastImages images(tiling.padded, c.sigma);
  std::vector<ContrastStats> stats;
  for (int ty = 0; ty < c.tiles_y; ++ty) {
    for (int tx = 0; tx < c.tiles_x; ++tx) {
      stats.push_back(images.stats({tx * tiling.tile.width, ty * tiling.tile.height,
                                    tiling.tile.width, tiling.tile.height}));
    }
  }
  return stats;
}

}  // namespace lumaslam::enhance
