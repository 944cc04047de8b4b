#pragma once
// Our own contrast-limited adaptive histogram equalisation (paper Eq. 9-10, 14-19), laid out
// like cv::CLAHE so that with the same grid and limit the two agree to +-1 gray level:
// per-tile 256-bin histograms on the image padded (BORDER_REFLECT_101) to a multiple of the
// grid, clipping with uniform redistribution, CDF lookup tables and bilinear interpolation
// between the four nearest tile centres. Unlike cv::CLAHE, every tile may have its own limit.
#include <opencv2/core.hpp>

namespace lumaslam::enhance {

class Clahe {
 public:
  // Throws Error unless 1 <= tiles <= 64 in both directions.
  Clahe(int tiles_x, int tiles_y);

  // One clip limit for every tile, in OpenCV's normalised units (absolute clip count =
  // limit * tile_pixels / 256, at least 1); limit <= 0 disables clipping.
  cv::Mat apply(const cv::Mat& gray, double limit) const;
  // tile_limits: CV_64FC1, tiles_y x tiles_x, one normalised limit per tile.
  cv::Mat apply(const cv::Mat& gray, const cv::Mat& tile_limits) const;

  // The image the tile histograms are taken from (the input, padded when its size is not a
  // multiple of the grid) and the tile size in it.
  struct Tiling {
    cv::Mat padded;
    cv::Size tile;
  };
  Tiling tiling(const cv::Mat& gray) const;

  int tilesX() const { return tiles_x_; }
  int tilesY() const { return tiles_y_; }

 private:
  cv::Mat tileLookupTables(const Tiling& tiling, const cv::Mat& tile_limits) const;
  cv::Mat interpolate(const cv::Mat& gray, const cv::Mat& luts, cv::Size tile) const;

  int tiles_x_;
  int tiles_y_;
};

}  // namespace lumaslam::enhance
