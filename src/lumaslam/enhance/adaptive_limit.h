#pragma once
// Adaptive CLAHE clip limit (paper Eq. 11-13): limit = gain * ((1 - sigma/sigma_max) +
// (1 - d/d_max)) + c, with sigma the std of intensity (Eq. 12) or of the gradient magnitude,
// d the variance of the Laplacian (Eq. 13). Ratios are clamped to [0, 1], so with gain 1 the
// limit lies in [c, c + 2] and equals c when sigma = sigma_max and d = d_max.
#include <opencv2/core.hpp>

#include "lumaslam/enhance/enhancer_params.h"

namespace lumaslam::enhance {

struct ContrastStats {
  double sigma = 0.0;
  double d = 0.0;
};

// Per-pixel images the statistics are taken from, so tiles can share one pass.
class ContrastImages {
 public:
  ContrastImages(const cv::Mat& gray, SigmaSource source);
  // Statistics over `region` (the whole image when empty).
  ContrastStats stats(const cv::Rect& region = {}) const;

 private:
  cv::Mat sigma_image_;  // intensity (8U) or gradient magnitude (32F)
  cv::Mat laplacian_;    // 16S
};

// Whole-image statistics, each a single pass without intermediate images (intensity sigma:
// meanStdDev; gradient sigma and d: fused SIMD passes); equal to
// ContrastImages(gray, source).stats() up to rounding.
ContrastStats measureContrast(const cv::Mat& gray, SigmaSource source);
// Eq. 13: variance of cv::Laplacian(gray, CV_16S) (3x3 kernel, BORDER_REFLECT_101).
double laplacianVariance(const cv::Mat& gray);
// Std of the Sobel (3x3, BORDER_REFLECT_101) gradient magnitude, the `gradient` sigma.
double gradientMagnitudeStd(const cv::Mat& gray);

class ClipLimitModel {
 public:
  // Zero sigma_max / d_max in params mean "use the prior".
  explicit ClipLimitModel(const ClaheParams& params);

  double limit(const ContrastStats& stats) const;  // Eq. 11
  // Online mode: raises the maxima to cover `stats` (no-op for fixed maxima).
  void observe(const ContrastStats& stats);

  double sigmaMax() const { return sigma_max_; }
  double dMax() const { return d_max_; }

 private:
  double base_;
  double gain_;
  bool online_;
  double sigma_max_;
  double d_max_;
};

// Running maxima of sigma and d over a pass through a sequence (`enhance --calibrate`).
struct ContrastMaxima {
  double sigma_max = 0.0;
  double d_max = 0.0;
  void observe(const ContrastStats& stats);
};

}  // namespace lumaslam::enhance
