#include "lumaslam/enhance/adaptive_limit.h"

#include <algorithm>
#include <array>
#include <cstdint>

#include <opencv2/core/hal/intrin.hpp>
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

namespace {

// Index of row/column i in [-1, n] under BORDER_REFLECT_101 (n = 1 reflects onto itself).
int reflect101(int i, int n) {
  if (n == 1) return 0;
  if (i < 0) return 1;
  if (i >= n) return n - 2;
  return i;
}

struct LaplacianSums {
  std::int64_t sum = 0;
  std::int64_t squares = 0;
  void add(int value) {
    sum += value;
    squares += static_cast<std::int64_t>(value) * value;
  }
};

int laplacianAt(const uchar* up, const uchar* row, const uchar* down, int x, int cols) {
  return row[reflect101(x - 1, cols)] + row[reflect101(x + 1, cols)] + up[x] + down[x] - 4 * row[x];
}

// Interior columns [1, cols - 1) of one row, 16-bit lanes; returns the first column not done.
int laplacianRowSimd(const uchar* up, const uchar* row, const uchar* down, int cols,
                     LaplacianSums& sums) {
  int x = 1;
#if CV_SIMD
  constexpr int kLanes = cv::v_int16::nlanes;
  // Flushed to 64 bits every kFlush vectors: a lane gains at most 2 * 1020^2 per vector.
  constexpr int kFlush = 512;
  const cv::v_int16 ones = cv::vx_setall_s16(1);
  while (x + kLanes <= cols - 1) {
    cv::v_int32 sum = cv::vx_setzero_s32();
    cv::v_int32 squares = cv::vx_setzero_s32();
    for (int n = 0; n < kFlush && x + kLanes <= cols - 1; ++n, x += kLanes) {
      const auto load = [x](const uchar* p, int dx) {
        return cv::v_reinterpret_as_s16(cv::vx_load_expand(p + x + dx));
      };
      const cv::v_int16 lap =
          load(row, -1) + load(row, 1) + load(up, 0) + load(down, 0) - cv::v_shl<2>(load(row, 0));
      sum += cv::v_dotprod(lap, ones);
      squares += cv::v_dotprod(lap, lap);
    }
    std::array<int, cv::v_int32::nlanes> lanes{};
    cv::v_store(lanes.data(), sum);
    for (const int lane : lanes) sums.sum += lane;
    cv::v_store(lanes.data(), squares);
    for (const int lane : lanes) sums.squares += lane;
  }
#endif
  for (; x < cols - 1; ++x) sums.add(laplacianAt(up, row, down, x, cols));
  return x;
}

}  // namespace

double laplacianVariance(const cv::Mat& gray) {
  CV_Assert(gray.type() == CV_8UC1 && !gray.empty());
  LaplacianSums sums;
  for (int y = 0; y < gray.rows; ++y) {
    const uchar* up = gray.ptr<uchar>(reflect101(y - 1, gray.rows));
    const uchar* row = gray.ptr<uchar>(y);
    const uchar* down = gray.ptr<uchar>(reflect101(y + 1, gray.rows));
    sums.add(laplacianAt(up, row, down, 0, gray.cols));
    if (gray.cols > 1) {
      laplacianRowSimd(up, row, down, gray.cols, sums);
      sums.add(laplacianAt(up, row, down, gray.cols - 1, gray.cols));
    }
  }
  const double n = static_cast<double>(gray.total());
  const double mean = static_cast<double>(sums.sum) / n;
  return std::max(static_cast<double>(sums.squares) / n - mean * mean, 0.0);
}

ContrastStats measureContrast(const cv::Mat& gray, SigmaSource source) {
  if (source == SigmaSource::kGradient) return ContrastImages(gray, source).stats();
  CV_Assert(gray.type() == CV_8UC1 && !gray.empty());
  cv::Scalar mean;
  cv::Scalar sigma;
  cv::meanStdDev(gray, mean, sigma);  // Eq. 12
  return {sigma[0], laplacianVariance(gray)};
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
