#pragma once
// Quality gate of paper Eq. 1-3: decides whether a frame needs brightness compensation.
#include <opencv2/core.hpp>

#include "lumaslam/enhance/enhancer_params.h"

namespace lumaslam::enhance {

struct BrightnessStats {
  double mean = 0.0;  // Lmean (Eq. 1), brightness normalised to [0, 1]
  double std = 0.0;   // Lstd (Eq. 2)
};

// Mean and std of an 8-bit single-channel image, in [0, 1] units.
BrightnessStats measureBrightness(const cv::Mat& channel);

class QualityGate {
 public:
  explicit QualityGate(const QualityGateParams& params) : params_(params) {}
  // Q of Eq. 3: false (leave as is) iff |Lmean - 0.5| < epsilon and Lstd > theta.
  bool needsCompensation(const BrightnessStats& stats) const;

 private:
  QualityGateParams params_;
};

}  // namespace lumaslam::enhance
