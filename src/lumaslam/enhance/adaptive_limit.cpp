#include "lumaslam/enhance/adaptive_limit.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace lumaslam::enhance {

ContrastImages::ContrastImages(const cv::Mat& gray, SigmaSource source) {
  CV_Assert(gray.type() == CV_8UC1 && !gray.empty());
  cv::Laplacian(gray, laplacian_, CV_16S);
  if (source == SigmaSource::kIntensity) {
    sigma_image_ = gray;
    return;
  }
  // 16-bit Sobel is exact for 8-bit input and much faster than float; the squared magnitude
  // is exact in float (< 2^21), then one vectorised square root.
  cv::Mat dx;
  cv::Mat dy;
  cv::Sobel(gray, dx, CV_16S, 1, 0);
  cv::Sobel(gray, dy, CV_16S, 0, 1);
  cv::Mat squared(gray.size(), CV_32FC1);
  for (int y = 0; y < gray.rows; ++y) {
    const short* gx = dx.ptr<short>(y);
    const short* gy = dy.ptr<short>(y);
    float* out = squared.ptr<float>(y);
    for (int x = 0; x < gray.cols; ++x) {
      out[x] = static_cast<float>(gx[x] * gx[x] + gy[x] * gy[x]);
    }
  }
  cv::sqrt(squared, sigma_image_);
}

ContrastStats ContrastImages::stats(const cv::Rect& region) const {
  const cv::Rect roi = region.empty() ? cv::Rect({}, laplacian_.size()) : region;
  cv::Scalar mean;
  cv::Scalar sigma;
  cv::meanStdDev(sigma_image_(roi), mean, sigma);  // Eq. 12
  cv::Scalar lap_std;
  cv::meanStdDev(laplacian_(roi), mean, lap_std);  // Eq. 13: d is the variance
  return {sigma[0], lap_std[0] * lap_std[0]};
}

ContrastStats measureContrast(const cv::Mat& gray, SigmaSource source) {
  return ContrastImages(gray, source).stats();
}

ClipLimitModel::ClipLimitModel(const ClaheParams& params)
    : base_(params.base),
      gain_(params.gain),
      online_(params.maxima == MaximaSource::kOnline),
      sigma_max_(params.sigma_max > 0.0 ? params.sigma_max : sigmaMaxPrior(params.sigma)),
      d_max_(params.d_max > 0.0 ? params.d_max : laplacianVarianceMaxPrior()) {}

double ClipLimitModel::limit(const ContrastStats& stats) const {
  const double sigma_ratio = std::clamp(stats.sigma / sigma_max_, 0.0, 1.0);
  const double d_ratio = std::clamp(stats.d / d_max_, 0.0, 1.0);
  return gain_ * ((1.0 - sigma_ratio) + (1.0 - d_ratio)) + base_;
}

void ClipLimitModel::observe(const ContrastStats& stats) {
  if (!online_) return;
  sigma_max_ = std::max(sigma_max_, stats.sigma);
  d_max_ = std::max(d_max_, stats.d);
}

void ContrastMaxima::observe(const ContrastStats& stats) {
  sigma_max = std::max(sigma_max, stats.sigma);
  d_max = std::max(d_max, stats.d);
}

}  // namespace lumaslam::enhance
