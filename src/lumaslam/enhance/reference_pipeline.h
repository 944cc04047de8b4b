#pragma once
// The enhancement written stage by stage, the way paper section 3.1 reads: every stage makes
// its own full image (channel, compensated channel, 16-bit Laplacian, CLAHE output, colour).
// Kept as the oracle the fused Enhancer is tested against (+-1 gray level) and as the
// baseline its speed is benchmarked against; not used by the system.
#include <opencv2/core.hpp>

#include "lumaslam/enhance/adaptive_limit.h"
#include "lumaslam/enhance/enhancer.h"

namespace lumaslam::enhance {

class ReferenceEnhancer {
 public:
  explicit ReferenceEnhancer(EnhancerParams params);
  // 8-bit gray or BGR only.
  EnhancedFrame enhance(const cv::Mat& image);

 private:
  EnhancerParams params_;
  ClipLimitModel limit_model_;
};

}  // namespace lumaslam::enhance
