#include "lumaslam/enhance/adaptive_limit.h"

#include <algorithm>
#include <array>
#include <cmath>
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

struct MagnitudeSums {
  double sum = 0.0;
  double squares = 0.0;
  void add(float magnitude) {
    const double m = magnitude;
    sum += m;
    squares += m * m;
  }
};

// |(Sobel x, Sobel y)| (3x3, BORDER_REFLECT_101) at column x, as float like the image path.
float gradientAt(const uchar* up, const uchar* row, const uchar* down, int x, int cols) {
  const int l = reflect101(x - 1, cols);
  const int r = reflect101(x + 1, cols);
  const int gx = (up[r] + 2 * row[r] + down[r]) - (up[l] + 2 * row[l] + down[l]);
  const int gy = (down[l] + 2 * down[x] + down[r]) - (up[l] + 2 * up[x] + up[r]);
  return std::sqrt(static_cast<float>(gx * gx + gy * gy));
}

// Interior columns [1, cols - 1) of one row; returns the first column not done.
int gradientRowSimd(const uchar* up, const uchar* row, const uchar* down, int cols,
                    MagnitudeSums& sums) {
  int x = 1;
#if CV_SIMD && CV_SIMD_64F
  constexpr int kLanes = cv::v_int16::nlanes;
  cv::v_float64 sum = cv::vx_setzero_f64();
  cv::v_float64 squares = cv::vx_setzero_f64();
  const auto accumulate = [&](const cv::v_int32& gx, const cv::v_int32& gy) {
    const cv::v_float32 m = cv::v_sqrt(cv::v_cvt_f32(gx * gx + gy * gy));
    const cv::v_float64 lo = cv::v_cvt_f64(m);
    const cv::v_float64 hi = cv::v_cvt_f64_high(m);
    sum += lo + hi;
    squares = cv::v_fma(lo, lo, cv::v_fma(hi, hi, squares));
  };
  for (; x + kLanes <= cols - 1; x += kLanes) {
    const auto load = [x](const uchar* p, int dx) {
      return cv::v_reinterpret_as_s16(cv::vx_load_expand(p + x + dx));
    };
    const cv::v_int16 gx = (load(up, 1) + cv::v_shl<1>(load(row, 1)) + load(down, 1)) -
                           (load(up, -1) + cv::v_shl<1>(load(row, -1)) + load(down, -1));
    const cv::v_int16 gy = (load(down, -1) + cv::v_shl<1>(load(down, 0)) + load(down, 1)) -
                           (load(up, -1) + cv::v_shl<1>(load(up, 0)) + load(up, 1));
    cv::v_int32 gx_lo;
    cv::v_int32 gx_hi;
    cv::v_int32 gy_lo;
    cv::v_int32 gy_hi;
    cv::v_expand(gx, gx_lo, gx_hi);
    cv::v_expand(gy, gy_lo, gy_hi);
    accumulate(gx_lo, gy_lo);
    accumulate(gx_hi, gy_hi);
  }
  sums.sum += cv::v_reduce_sum(sum);
  sums.squares += cv::v_reduce_sum(squares);
#endif
  for (; x < cols - 1; ++x) sums.add(gradientAt(up, row, down, x, cols));
  return x;
}

// Sums a 3x3 filter's response over every pixel (BORDER_REFLECT_101): border columns with
// `at`, the interior of each row with `row_simd`.
template <typename Sums, typename At, typename RowSimd>
Sums sumOverRows(const cv::Mat& gray, At at, RowSimd row_simd) {
  Sums sums;
  for (int y = 0; y < gray.rows; ++y) {
    const uchar* up = gray.ptr<uchar>(reflect101(y - 1, gray.rows));
    const uchar* row = gray.ptr<uchar>(y);
    const uchar* down = gray.ptr<uchar>(reflect101(y + 1, gray.rows));
    sums.add(at(up, row, down, 0, gray.cols));
    if (gray.cols > 1) {
      row_simd(up, row, down, gray.cols, sums);
      sums.add(at(up, row, down, gray.cols - 1, gray.cols));
    }
  }
  return sums;
}

}  // namespace

double gradientMagnitudeStd(const cv::Mat& gray) {
  CV_Assert(gray.type() == CV_8UC1 && !gray.empty());
  const auto sums = sumOverRows<MagnitudeSums>(gray, gradientAt, gradientRowSimd);
  const double n = static_cast<double>(gray.total());
  const double mean = sums.sum / n;
  return std::sqrt(std::max(sums.squares / n - mean * mean, 0.0));
}

double laplacianVariance(const cv::Mat& gray) {
  CV_Assert(gray.type() == CV_8UC1 && !gray.empty());
  const auto sums = sumOverRows<LaplacianSums>(gray, laplacianAt, laplacianRowSimd);
  const double n = static_cast<double>(gray.total());
  const double mean = static_cast<double>(sums.sum) / n;
  return std::max(static_cast<double>(sums.squares) / n - mean * mean, 0.0);
}

ContrastStats measureContrast(const cv::Mat& gray, SigmaSource source) {
  CV_Assert(gray.type() == CV_8UC1 && !gray.empty());
  if (source == SigmaSource::kGradient)
    return {gradientMagnitudeStd(gray), laplacianVariance(gray)};
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
