#pragma once
// The multi-level adaptive enhancement of paper section 3.1, one frame at a time:
// quality gate (Eq. 1-3) -> brightness compensation (Eq. 4) -> work channel (V of HSV,
// Eq. 5-8, or gray) -> adaptive-limit CLAHE (Eq. 9-19) -> colour rebuilt from the channel.
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

class Enhancer {
 public:
  explicit Enhancer(EnhancerParams params);

  // Accepts 8-bit gray, BGR or BGRA (alpha is dropped). Throws Error for an empty image,
  // another depth or channel count. Not const: online maxima learn from every frame.
  EnhancedFrame enhance(const cv::Mat& image);

  // Contrast statistics of the channel as it reaches CLAHE: one entry for the whole image,
  // or one per tile in local mode. `enhance --calibrate` takes their maxima.
  std::vector<ContrastStats> contrastOf(const cv::Mat& image) const;

  const EnhancerParams& params() const { return params_; }
  const ClipLimitModel& limitModel() const { return limit_model_; }

 private:
  struct Prepared {
    cv::Mat bgr;       // empty for gray input
    cv::Mat channel;   // work channel before compensation
    cv::Mat adjusted;  // after the gate / compensation
    FrameReport report;
  };
  Prepared prepare(const cv::Mat& image) const;
  cv::Mat equalise(const cv::Mat& channel, FrameReport& report);

  EnhancerParams params_;
  QualityGate gate_;
  BrightnessCompensation compensation_;
  Clahe clahe_;
  ClipLimitModel limit_model_;
};

}  // namespace lumaslam::enhance
