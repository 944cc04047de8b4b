#include "lumaslam/enhance/clahe.h"

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::enhance {
namespace {

constexpr int kBins = 256;

void checkInput(const cv::Mat& gray) {
  if (gray.empty()) fail("CLAHE: empty image");
  if (gray.type() != CV_8UC1)
    fail("CLAHE: expected an 8-bit single-channel image, got type {}",
         cv::typeToString(gray.type()));
}

// Eq. 10, 14, 15: clip at `clip` and spread the excess E uniformly; the E mod 256 remainder
// goes one count each to evenly spaced bins so the histogram keeps its total.
void clipAndRedistribute(int* hist, int clip) {
  int excess = 0;
  for (int g = 0; g < kBins; ++g) {
    if (hist[g] > clip) {
      excess += hist[g] - clip;
      hist[g] = clip;
    }
  }
  const int batch = excess / kBins;
  int remainder = excess - batch * kBins;
  for (int g = 0; g < kBins; ++g) hist[g] += batch;
  if (remainder > 0) {
    const int step = std::max(kBins / remainder, 1);
    for (int i = 0; i < kBins && remainder > 0; i += step, --remainder) ++hist[i];
  }
}

}  // namespace

Clahe::Clahe(int tiles_x, int tiles_y) : tiles_x_(tiles_x), tiles_y_(tiles_y) {
  if (tiles_x < 1 || tiles_y < 1 || tiles_x > 64 || tiles_y > 64) {
    fail("CLAHE: tile grid {}x{} out of range (1..64 each way)", tiles_x, tiles_y);
  }
}

Clahe::Tiling Clahe::tiling(const cv::Mat& gray) const {
  checkInput(gray);
  Tiling result;
  if (gray.cols % tiles_x_ == 0 && gray.rows % tiles_y_ == 0) {
    result.padded = gray;
  } else {
    // Same padding as cv::CLAHE: both directions grow when either is not a multiple.
    cv::copyMakeBorder(gray, result.padded, 0, tiles_y_ - gray.rows % tiles_y_, 0,
                       tiles_x_ - gray.cols % tiles_x_, cv::BORDER_REFLECT_101);
  }
  result.tile = {result.padded.cols / tiles_x_, result.padded.rows / tiles_y_};
  return result;
}

cv::Mat Clahe::apply(const cv::Mat& gray, double limit) const {
  return apply(gray, cv::Mat(tiles_y_, tiles_x_, CV_64FC1, cv::Scalar(limit)));
}

cv::Mat Clahe::apply(const cv::Mat& gray, const cv::Mat& tile_limits) const {
  checkInput(gray);
  const Tiling grid = tiling(gray);
  cv::Mat histograms = tileHistograms(grid);
  const cv::Mat luts = lookupTables(histograms, tile_limits, grid.tile.area());
  cv::Mat out;
  interpolate(gray, luts, grid.tile, out);
  return out;
}

cv::Mat Clahe::tileHistograms(const Tiling& grid) const {
  cv::Mat histograms(tiles_y_ * tiles_x_, kBins, CV_32SC1, cv::Scalar(0));
  for (int ty = 0; ty < tiles_y_; ++ty) {
    for (int tx = 0; tx < tiles_x_; ++tx) {
      const cv::Rect rect(tx * grid.tile.width, ty * grid.tile.height, grid.tile.width,
                          grid.tile.height);
      accumulateHistogram(grid.padded(rect), histograms.ptr<int>(ty * tiles_x_ + tx));
    }
  }
  return histograms;
}

cv::Mat Clahe::lookupTables(cv::Mat& histograms, const cv::Mat& tile_limits,
                            int tile_pixels) const {
  if (tile_limits.type() != CV_64FC1 || tile_limits.rows != tiles_y_ ||
      tile_limits.cols != tiles_x_) {
    fail("CLAHE: tile limits must be a {}x{} CV_64FC1 matrix", tiles_y_, tiles_x_);
  }
  CV_Assert(histograms.type() == CV_32SC1 && histograms.rows == tiles_y_ * tiles_x_ &&
            histograms.cols == kBins && histograms.isContinuous());
  const float lut_scale = static_cast<float>(kBins - 1) / static_cast<float>(tile_pixels);
  cv::Mat luts(tiles_y_ * tiles_x_, kBins, CV_8UC1);
  for (int t = 0; t < histograms.rows; ++t) {
    int* hist = histograms.ptr<int>(t);
    const double limit = tile_limits.at<double>(t / tiles_x_, t % tiles_x_);
    if (limit > 0.0) {
      const int clip = std::max(static_cast<int>(limit * tile_pixels / kBins), 1);
      clipAndRedistribute(hist, clip);
    }
    uchar* lut = luts.ptr<uchar>(t);
    int cumulative = 0;
    for (int g = 0; g < kBins; ++g) {
      cumulative += hist[g];
      lut[g] = cv::saturate_cast<uchar>(static_cast<float>(cumulative) * lut_scale);
    }
  }
  return luts;
}

// Eq. 16-19: each pixel blends the lookup tables of the four tiles whose centres surround
// it; outside the outermost centres the nearest tiles are used (weights clamp like cv::CLAHE).
void Clahe::interpolate(const cv::Mat& gray, const cv::Mat& luts, cv::Size tile,
                        cv::Mat& out) const {
  CV_Assert(gray.type() == CV_8UC1 && luts.type() == CV_8UC1 && luts.rows == tiles_x_ * tiles_y_ &&
            luts.cols == kBins);
  if (tiles_x_ == 1 && tiles_y_ == 1) {
    // All four "neighbours" are the one tile: the blend is the table itself.
    cv::LUT(gray, luts, out);
    return;
  }
  const float inv_tile_w = 1.0f / static_cast<float>(tile.width);
  const float inv_tile_h = 1.0f / static_cast<float>(tile.height);
  std::vector<int> left(gray.cols);
  std::vector<int> right(gray.cols);
  std::vector<float> u(gray.cols);
  for (int x = 0; x < gray.cols; ++x) {
    const float tx = static_cast<float>(x) * inv_tile_w - 0.5f;
    const int tx1 = cvFloor(tx);
    u[x] = tx - static_cast<float>(tx1);  // Eq. 16
    left[x] = std::max(tx1, 0) * kBins;
    right[x] = std::min(tx1 + 1, tiles_x_ - 1) * kBins;
  }
  out.create(gray.size(), CV_8UC1);
  for (int y = 0; y < gray.rows; ++y) {
    const float ty = static_cast<float>(y) * inv_tile_h - 0.5f;
    const int ty1 = cvFloor(ty);
    const float v = ty - static_cast<float>(ty1);  // Eq. 17
    const uchar* top = luts.ptr<uchar>(std::max(ty1, 0) * tiles_x_);
    const uchar* bottom = luts.ptr<uchar>(std::min(ty1 + 1, tiles_y_ - 1) * tiles_x_);
    const uchar* in = gray.ptr<uchar>(y);
    uchar* dst = out.ptr<uchar>(y);
    for (int x = 0; x < gray.cols; ++x) {
      const int g = in[x];
      const float f00 = top[left[x] + g];  // Eq. 18
      const float f10 = top[right[x] + g];
      const float f01 = bottom[left[x] + g];
      const float f11 = bottom[right[x] + g];
      const float w = u[x];
      dst[x] = cv::saturate_cast<uchar>((f00 * (1.0f - w) + f10 * w) * (1.0f - v) +
                                        (f01 * (1.0f - w) + f11 * w) * v);  // Eq. 19
    }
  }
}

// Four interleaved partial histograms: runs of equal pixels (common in dark frames) would
// otherwise make every increment wait for the previous one to the same bin.
void accumulateHistogram(const cv::Mat& gray, int* hist) {
  CV_Assert(gray.type() == CV_8UC1);
  std::array<std::array<int, kBins>, 4> partial{};
  for (int y = 0; y < gray.rows; ++y) {
    const uchar* row = gray.ptr<uchar>(y);
    int x = 0;
    for (; x + 4 <= gray.cols; x += 4) {
      ++partial[0][row[x]];
      ++partial[1][row[x + 1]];
      ++partial[2][row[x + 2]];
      ++partial[3][row[x + 3]];
    }
    for (; x < gray.cols; ++x) ++partial[0][row[x]];
  }
  for (int g = 0; g < kBins; ++g) {
    hist[g] += partial[0][g] + partial[1][g] + partial[2][g] + partial[3][g];
  }
}

}  // namespace lumaslam::enhance
