#include "lumaslam/enhance/enhancer.h"

#include <algorithm>
#include <array>

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

Enhancer::Input Enhancer::prepare(const cv::Mat& image) const {
  Input input;
  const cv::Mat normalised = normaliseInput(image);
  if (normalised.channels() == 1) {
    input.channel = normalised;  // gray is its own V
  } else {
    input.bgr = normalised;
    if (params_.channel == WorkChannel::kValue) {
      valueChannel(normalised, input.channel);
    } else {
      cv::cvtColor(normalised, input.channel, cv::COLOR_BGR2GRAY);
    }
  }
  return input;
}

cv::Mat Enhancer::compensationTable(const cv::Mat& channel, FrameReport& report) const {
  report.brightness = measureBrightness(channel);
  report.compensated = params_.compensation.enabled && gate_.needsCompensation(report.brightness);
  return report.compensated ? compensation_.lookupTable(report.brightness.mean) : cv::Mat();
}

cv::Mat Enhancer::tileLimits(const cv::Mat& adjusted, const Clahe::Tiling& tiling,
                             FrameReport& report) {
  const auto& c = params_.clahe;
  if (c.limit_mode == ClipLimitMode::kFixed) {
    report.limit = c.fixed_limit;
    return cv::Mat(c.tiles_y, c.tiles_x, CV_64FC1, cv::Scalar(c.fixed_limit));
  }
  if (c.limit_mode == ClipLimitMode::kGlobal) {
    const ContrastStats stats = measureContrast(adjusted, c.sigma);
    limit_model_.observe(stats);
    report.contrast = stats;
    report.limit = limit_model_.limit(stats);
    return cv::Mat(c.tiles_y, c.tiles_x, CV_64FC1, cv::Scalar(*report.limit));
  }
  // Local: Eq. 11 per tile, from the tile's own statistics.
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
  return limits;
}

EnhancementPlan Enhancer::planFor(const cv::Mat& channel) {
  EnhancementPlan plan;
  plan.compensation = compensationTable(channel, plan.report);
  cv::Mat adjusted = channel;
  if (!plan.compensation.empty()) {
    cv::LUT(channel, plan.compensation, adjusted_);
    adjusted = adjusted_;
  }
  if (params_.clahe.enabled) {
    plan.limits = tileLimits(adjusted, clahe_.tiling(adjusted), plan.report);
  }
  buildTables(adjusted, plan);
  return plan;
}

EnhancementPlan Enhancer::planFor(const cv::Mat& channel, const EnhancementPlan& decisions) const {
  EnhancementPlan plan;
  plan.report = decisions.report;
  plan.compensation = decisions.compensation;
  plan.limits = decisions.limits;
  cv::Mat adjusted = channel;
  if (!plan.compensation.empty()) {
    adjusted = cv::Mat();  // a fresh image: cv::LUT into a header of `channel` would overwrite it
    cv::LUT(channel, plan.compensation, adjusted);
  }
  buildTables(adjusted, plan);
  return plan;
}

void Enhancer::buildTables(const cv::Mat& adjusted, EnhancementPlan& plan) const {
  plan.size = adjusted.size();
  plan.tile = adjusted.size();
  if (!params_.clahe.enabled) {
    plan.luts = plan.compensation;
    return;
  }
  const Clahe::Tiling tiling = clahe_.tiling(adjusted);
  cv::Mat histograms = clahe_.tileHistograms(tiling);
  plan.tile = tiling.tile;
  plan.luts = clahe_.lookupTables(histograms, plan.limits, tiling.tile.area());
  if (!plan.compensation.empty()) {
    // Fold Eq. 4 into the CLAHE tables: channel -> compensated -> equalised in one lookup.
    const uchar* compensate = plan.compensation.ptr<uchar>();
    for (int t = 0; t < plan.luts.rows; ++t) {
      uchar* lut = plan.luts.ptr<uchar>(t);
      std::array<uchar, 256> folded{};
      for (int v = 0; v < 256; ++v) folded[v] = lut[compensate[v]];
      std::copy(folded.begin(), folded.end(), lut);
    }
  }
}

EnhancedFrame Enhancer::applyTo(const Input& input, const EnhancementPlan& plan) const {
  if (input.channel.size() != plan.size) {
    fail("enhance: the image is {}x{}, the enhancement plan was made for {}x{}", input.channel.cols,
         input.channel.rows, plan.size.width, plan.size.height);
  }
  EnhancedFrame frame;
  frame.report = plan.report;
  cv::Mat enhanced;
  if (plan.luts.empty()) {
    enhanced = input.channel;
  } else if (plan.luts.rows == 1) {
    cv::LUT(input.channel, plan.luts, enhanced);
  } else {
    clahe_.interpolate(input.channel, plan.luts, plan.tile, enhanced);
  }
  if (input.bgr.empty()) {
    frame.colour = enhanced;
    frame.gray = enhanced;
    return frame;
  }
  rebuildColour(input.bgr, input.channel, enhanced, frame.colour);
  if (params_.channel == WorkChannel::kGray) {
    frame.gray = enhanced;
  } else {
    cv::cvtColor(frame.colour, frame.gray, cv::COLOR_BGR2GRAY);
  }
  return frame;
}

EnhancedFrame Enhancer::enhance(const cv::Mat& image) {
  const Input input = prepare(image);
  return applyTo(input, planFor(input.channel));
}

EnhancementPlan Enhancer::plan(const cv::Mat& image) {
  return planFor(prepare(image).channel);
}

EnhancedFrame Enhancer::apply(const cv::Mat& image, const EnhancementPlan& plan) const {
  return applyTo(prepare(image), plan);
}

EnhancedFrame Enhancer::enhanceRightWith(const cv::Mat& right,
                                         const EnhancementPlan& left_plan) const {
  switch (params_.stereo) {
    case StereoMapping::kShared:
      return apply(right, left_plan);
    case StereoMapping::kDecisions:
      return enhanceWith(right, left_plan);
    case StereoMapping::kIndependent:
      break;
  }
  fail(
      "Enhancer: Enhancement.stereo 'independent' enhances the right image with its own "
      "Enhancer, not with the left image's plan");
}

EnhancedFrame Enhancer::enhanceWith(const cv::Mat& image, const EnhancementPlan& decisions) const {
  const Input input = prepare(image);
  return applyTo(input, planFor(input.channel, decisions));
}

std::vector<ContrastStats> Enhancer::contrastOf(const cv::Mat& image) const {
  const Input input = prepare(image);
  FrameReport report;
  const cv::Mat table = compensationTable(input.channel, report);
  const cv::Mat adjusted =
      table.empty() ? input.channel : compensation_.apply(input.channel, report.brightness.mean);
  const auto& c = params_.clahe;
  if (c.limit_mode != ClipLimitMode::kLocal) return {measureContrast(adjusted, c.sigma)};
  const Clahe::Tiling tiling = clahe_.tiling(adjusted);
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
