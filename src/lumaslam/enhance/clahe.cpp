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

// Eq. 9: histogram of one tile.
void tileHistogram(const cv::Mat& tile, std::array<int, kBins>& hist) {
  hist.fill(0);
  for (int y = 0; y < tile.rows; ++y) {
    const uchar* row = tile.ptr<uchar>(y);
    int x = 0;
    for (; x + 4 <= tile.cols; x += 4) {
      ++hist[row[x]];
      ++hist[row[x + 1]];
      ++hist[row[x + 2]];
      ++hist[row[x + 3]];
    }
    for (; x < tile.cols; ++x) ++hist[row[x]];
  }
}

// Eq. 10, 14, 15: clip at `clip` and spread the excess E uniformly; the E mod 256 remainder
// goes one count each to evenly spaced bins so the histogram keeps its total.
void clipAndRedistribute(std::array<int, kBins>& hist, int clip) {
  int excess = 0;
  for (int& count : hist) {
    if (count > clip) {
      excess += count - clip;
      count = clip;
    }
  }
  const int batch = excess / kBins;
  int remainder = excess - batch * kBins;
  for (int& count : hist) count += batch;
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
  if (tile_limits.type() != CV_64FC1 || tile_limits.rows != tiles_y_ ||
      tile_limits.cols != tiles_x_) {
    fail("CLAHE: tile limits must be a {}x{} CV_64FC1 matrix", tiles_y_, tiles_x_);
  }
  const Tiling grid = tiling(gray);
  return interpolate(gray, tileLookupTables(grid, tile_limits), grid.tile);
}

cv::Mat Clahe::tileLookupTables(const Tiling& grid, const cv::Mat& tile_limits) const {
  const int tile_pixels = grid.tile.area();
  const float lut_scale = static_cast<float>(kBins - 1) / static_cast<float>(tile_pixels);
  cv::Mat luts(tiles_y_ * tiles_x_, kBins, CV_8UC1);
  std::array<int, kBins> hist{};
  for (int ty = 0; ty < tiles_y_; ++ty) {
    for (int tx = 0; tx < tiles_x_; ++tx) {
      const cv::Rect rect(tx * grid.tile.width, ty * grid.tile.height, grid.tile.width,
                          grid.tile.height);
      tileHistogram(grid.padded(rect), hist);
      const double limit = tile_limits.at<double>(ty, tx);
      if (limit > 0.0) {
        const int clip = std::max(static_cast<int>(limit * tile_pixels / kBins), 1);
        clipAndRedistribute(hist, clip);
      }
      uchar* lut = luts.ptr<uchar>(ty * tiles_x_ + tx);
      int cumulative = 0;
      for (int g = 0; g < kBins; ++g) {
        cumulative += hist[g];
        lut[g] = cv::saturate_cast<uchar>(static_cast<float>(cumulative) * lut_scale);
      }
    }
  }
  return luts;
}

// Eq. 16-19: each pixel blends the lookup tables of the four tiles whose centres surround
// it; outside the outermost centres the nearest tiles are used (weights clamp like cv::CLAHE).
cv::Mat Clahe::interpolate(const cv::Mat& gray, const cv::Mat& luts, cv::Size tile) const {
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
  cv::Mat out(gray.size(), CV_8UC1);
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
  return out;
}

}  // namespace lumaslam::enhance
