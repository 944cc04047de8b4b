#pragma once
// The multi-level adaptive enhancement of paper section 3.1, one frame at a time:
// quality gate (Eq. 1-3) -> brightness compensation (Eq. 4) -> work channel (V of HSV,
// Eq. 5-8, or gray) -> adaptive-limit CLAHE (Eq. 9-19) -> colour rebuilt from the channel.
//
// Split in two so a stereo pair can share one mapping: plan() measures a frame and decides
// everything (gate, compensation table, CLAHE limit and tables, with the compensation folded
// into the tables); apply() maps any frame of the same size through that plan in one lookup
// (or one interpolation) per pixel, then rebuilds the colour.
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/enhance/adaptive_limit.h"
#include "lumaslam/enhance/brightness_compensation.h"
#include "lumaslam/enhance/clahe.h"
#include "lumaslam/enhance/enhancer_params.h"
#include "lumaslam/enhance/quality_gate.h"

namespace lumaslam::enhance {

struct FrameReport {
  BrightnessStats brightness;             // of the work channel before compensation
  bool compensated = false;               // Q = 1 and compensation enabled
  std::optional<ContrastStats> contrast;  // adaptive limits only (mean over tiles if local)
  std::optional<double> limit;            // CLAHE limit used (mean over tiles if local)
};

struct EnhancedFrame {
  cv::Mat colour;  // for the detector: 8-bit, 1 channel for gray input, else BGR
  cv::Mat gray;    // for tracking: the gray of the enhanced image
  FrameReport report;
};

// Everything decided about one frame: the decisions (gate -> compensation table, CLAHE
// limits), the resulting work-channel mapping as one 256-entry table per CLAHE tile
// (compensation folded in), and what was measured.
struct EnhancementPlan {
  FrameReport report;
  cv::Mat compensation;  // Eq. 4 table (CV_8UC1, 1x256); empty when the gate left the frame alone
  cv::Mat limits;        // CLAHE limit per tile (CV_64FC1, tiles_y x tiles_x); empty: CLAHE off
  cv::Size size;         // of the frame it was made for; apply() needs the same size
  cv::Size tile;         // CLAHE tile size (in the padded frame) the tables belong to
  cv::Mat luts;          // CV_8UC1, tiles x 256; one row: a plain lookup; empty: identity
};

class Enhancer {
 public:
  explicit Enhancer(EnhancerParams params);

  // Accepts 8-bit gray, BGR or BGRA (alpha is dropped). Throws Error for an empty image,
  // another depth or channel count. Not const: online maxima learn from every frame.
  EnhancedFrame enhance(const cv::Mat& image);

  // enhance() = apply(image, plan(image)), without computing the work channel twice.
  EnhancementPlan plan(const cv::Mat& image);
  // Thread-safe; throws Error when the image's size differs from the plan's.
  EnhancedFrame apply(const cv::Mat& image, const EnhancementPlan& plan) const;
  // Takes the decisions of `decisions` (gate, compensation table, CLAHE limits) but builds
  // the CLAHE tables from this image's own histograms. Thread-safe.
  EnhancedFrame enhanceWith(const cv::Mat& image, const EnhancementPlan& decisions) const;
  // The right image of a stereo pair with the left image's plan, as params().stereo says:
  // `shared` applies the whole plan, `decisions` its decisions with the right image's own CLAHE
  // tables. Throws Error for `independent` (the right image then has its own Enhancer).
  EnhancedFrame enhanceRightWith(const cv::Mat& right, const EnhancementPlan& left_plan) const;

  // Contrast statistics of the channel as it reaches CLAHE: one entry for the whole image,
  // or one per tile in local mode. `enhance --calibrate` takes their maxima.
  std::vector<ContrastStats> contrastOf(const cv::Mat& image) const;

  const EnhancerParams& params() const { return params_; }
  const ClipLimitModel& limitModel() const { return limit_model_; }

 private:
  struct Input {
    cv::Mat bgr;      // empty for gray input
    cv::Mat channel;  // work channel before compensation
  };
  Input prepare(const cv::Mat& image) const;
  // Compensation table for this frame's channel, or empty when the gate leaves it alone.
  cv::Mat compensationTable(const cv::Mat& channel, FrameReport& report) const;
  EnhancementPlan planFor(const cv::Mat& channel);
  EnhancementPlan planFor(const cv::Mat& channel, const EnhancementPlan& decisions) const;
  void buildTables(const cv::Mat& adjusted, EnhancementPlan& plan) const;
  cv::Mat tileLimits(const cv::Mat& adjusted, const Clahe::Tiling& tiling, FrameReport& report);
  EnhancedFrame applyTo(const Input& input, const EnhancementPlan& plan) const;

  EnhancerParams params_;
  QualityGate gate_;
  BrightnessCompensation compensation_;
  Clahe clahe_;
  ClipLimitModel limit_model_;
  cv::Mat adjusted_;  // plan() scratch: the channel after compensation
};

}  // namespace lumaslam::enhance
